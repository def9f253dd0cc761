// Closest point on a triangle with its Voronoi feature (face, one of three edges, one of three vertices),
// robust on slivers and on degenerate triangles, plus the two exact-or-accurate triangle predicates the mesh
// needs. Internal.
//
// Method: q projects into the face when it is strictly on the inner side of all three edges, tested with the
// triangle's unit normal n (sides n·(e × (q − p0)) > 0); then the point is q − n·(n·(q − v0)) and the squared
// distance (n·(q − v0))². Otherwise the closest point lies on the boundary, and the minimum over the three
// edges (clamped projections, a clamped end being the vertex itself, bit for bit) is exact. A degenerate
// triangle (zero normal) is its boundary, so it takes the edge path too.
//
// Why the normal comes from accurateUnitNormal(): for a sliver of height h and size L, the cross product of
// rounded edge vectors has a direction error of ~ε·L/h, which moves a projected point by ~ε·L²/h. The edge
// differences are exact in double-double (two-sum), and the cross product is evaluated with fused
// multiply-adds, so the direction is right to a few ulps for any non-degenerate triangle.
#pragma once

#include "unidist/mesh.h"

#include <Eigen/Core>

namespace unidist::mesh {

struct TriangleClosest {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  /// q − point, computed from differences to the triangle's own vertices: it keeps its relative precision
  /// when the model is far from its origin, where q − point of the rounded point would not.
  Eigen::Vector3d gap = Eigen::Vector3d::Zero();
  double squaredDistance = 0;  ///< |gap|²
  TriangleFeature feature = TriangleFeature::Face;
  double b1 = 0, b2 = 0;  ///< barycentric coordinates of v1 and v2 (v0's is 1 − b1 − b2)
};

/// Closest point of triangle (v0, v1, v2) to q. `n` must be accurateUnitNormal(v0, v1, v2) (zero for a
/// degenerate triangle); it is passed in because the mesh precomputes it.
TriangleClosest closestOnTriangle(const Eigen::Vector3d& q, const Eigen::Vector3d& v0, const Eigen::Vector3d& v1,
                                  const Eigen::Vector3d& v2, const Eigen::Vector3d& n);

/// The same, computing the normal.
TriangleClosest closestOnTriangle(const Eigen::Vector3d& q, const Eigen::Vector3d& v0, const Eigen::Vector3d& v1,
                                  const Eigen::Vector3d& v2);

/// (v1 − v0) × (v2 − v0) accurate to a few ulps of its own size (double-double differences, FMA products).
Eigen::Vector3d accurateCross(const Eigen::Vector3d& v0, const Eigen::Vector3d& v1, const Eigen::Vector3d& v2);

/// Unit normal of the triangle (right-handed in v0 → v1 → v2), or zero when the area is exactly zero.
Eigen::Vector3d accurateUnitNormal(const Eigen::Vector3d& v0, const Eigen::Vector3d& v1, const Eigen::Vector3d& v2);

/// True when the three points are exactly collinear (or coincide): a floating-point filter, then an exact
/// expansion sum of each 2×2 minor of the cross product when the filter cannot decide.
bool zeroArea(const Eigen::Vector3d& v0, const Eigen::Vector3d& v1, const Eigen::Vector3d& v2);

/// Corner angle at p between p→a and p→b, in [0, π] (atan2 of |cross| and dot: accurate at 0 and π).
double cornerAngle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b);

}  // namespace unidist::mesh
