// Exact closest points between two triangles (internal). Disjoint triangles: the minimum over the 6
// vertex–triangle and 9 edge–edge distances (Ericson, "Real-Time Collision Detection" §5.2.4: for two
// disjoint triangles a closest pair always has one point at a vertex or both on edges; an edge pair whose
// closest points include an endpoint is a vertex pair already, so only interior edge–edge points are solved).
// Intersecting triangles (an edge of one crossing the other outside their common plane) give distance 0 with a
// point on the intersection; coplanar overlaps give 0 through the features themselves.
#pragma once

#include <Eigen/Core>

#include <limits>

namespace unidist::mesh {

struct TriangleTriangleClosest {
  Eigen::Vector3d pointA = Eigen::Vector3d::Zero();
  Eigen::Vector3d pointB = Eigen::Vector3d::Zero();
  double distance = 0;
  bool intersecting = false;  ///< an edge of one triangle was found crossing the other
};

/// a[0..2], b[0..2]: the vertices; na, nb: accurateUnitNormal of each (non-zero). When the distance is
/// proved (up to rounding of the coordinates) to be at least `cutoff`, the search may stop early and return
/// distance = +infinity: callers that only want pairs closer than a best-so-far pass it as the cutoff.
TriangleTriangleClosest closestTriangleTriangle(const Eigen::Vector3d* a, const Eigen::Vector3d& na,
                                                const Eigen::Vector3d* b, const Eigen::Vector3d& nb,
                                                double cutoff = std::numeric_limits<double>::infinity());

/// Whether segment [p, q] crosses triangle t (normal n) away from the triangle's plane; sets x to the crossing.
bool segmentCrossesTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d* t,
                            const Eigen::Vector3d& n, Eigen::Vector3d& x);

}  // namespace unidist::mesh
