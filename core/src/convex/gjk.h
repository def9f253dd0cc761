// Distance and penetration depth of two convex sets given only by their support maps (internal).
//
// GJK (Gilbert, Johnson & Keerthi 1988) with the signed-volume sub-distance of Montanari, Petrinic & Barbieri,
// "Improving the GJK algorithm for faster and more reliable distance queries between convex objects",
// ACM TOG 36(3), 2017: the closest point of a simplex to the origin is found from signed volumes/areas of the
// simplex and its faces projected on the best-conditioned coordinate plane, which stays reliable for the
// nearly degenerate simplices GJK produces on curved sets. When the sets overlap, EPA (van den Bergen 2001)
// grows a polytope inside the Minkowski difference A − B toward the face closest to the origin.
//
// Bounds (all proved up to floating-point rounding; D = A − B, h_D(n) = max over D of n·x):
//  * lower: for every unit n, signed distance >= −h_D(n) (a separating-axis gap when h_D(n) < 0, and
//    −PD >= −h_D(n) because the origin's distance to ∂D is at most h_D(n) when it is inside). GJK evaluates it
//    at n = −v/|v|, EPA at every face normal it tries.
//  * upper: |pointA − pointB| for hull points of A and B (GJK), and −(origin's distance to the boundary of the
//    EPA polytope) once that polytope, which lies inside D, contains the origin.
#pragma once

#include "cloud/point_support.h"

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products

#include <functional>
#include <limits>
#include <vector>

namespace unidist::detail {

/// World-frame support map of a convex set: a point of the set maximising d·p (d need not be unit).
using SupportFn = std::function<Eigen::Vector3d(const Eigen::Vector3d&)>;

/// The support map of the convex hull of `points` (non-empty; held by reference: they must outlive the map).
inline SupportFn supportOfPointSet(const std::vector<Eigen::Vector3d>& points) {
  return [&points](const Eigen::Vector3d& d) { return supportOfPoints(points, d); };
}

struct ConvexDistance {
  double distance = 0;  ///< signed: > 0 separation, < 0 = −(penetration depth = minimum translation distance)
  Eigen::Vector3d pointA = Eigen::Vector3d::Zero();  ///< world, on A's boundary; pointB − pointA = distance·normal
  Eigen::Vector3d pointB = Eigen::Vector3d::Zero();  ///< world, on B's boundary
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ(); ///< unit: A toward B; when penetrating, the way B moves to separate
  double lowerBound = 0, upperBound = 0;  ///< proved bounds on the signed distance (up to rounding)
  int iterations = 0;                     ///< GJK iterations + EPA iterations
  bool converged = false;                 ///< upperBound − lowerBound <= tolerance (and points certified, see below)
};

/// Signed distance of two convex sets (GJK; EPA when they overlap or touch). tolerance: absolute (unit: length),
/// > 0; 0 (or negative) means "as exact as double allows": max(1e-15 × size of A − B, a few ulps of the
/// coordinates). maxIterations caps the support evaluations of the GJK and EPA loops together (EPA on curved
/// sets needs ~100 for 1e-9; where the translation direction is not unique, e.g. concentric spheres, it would
/// need ~1/tolerance and stops at the cap with a bounded, uncertified answer: ~0.5 s at 100000).
/// converged: upperBound − lowerBound <= tolerance and the points are certified too (each within tolerance of
/// its set's boundary). Not converged: the interval is still proved; the value lies in it.
/// Touching sets give ~0 with bounds straddling 0; flat or needle-thin sets are handled. Thread-safe if the
/// support maps are. With measurePenetration false, overlapping sets skip EPA: the answer is GJK's (distance
/// ~0, lowerBound the proved separating-axis bound, possibly −inf) — for callers that need only a lower bound
/// on the distance of sets that cannot interpenetrate (surfaces).
ConvexDistance convexDistance(const SupportFn& a, const SupportFn& b, double tolerance, int maxIterations,
                              bool measurePenetration = true);

// ---- Building blocks, shared by gjk.cpp, epa.cpp and the pair functions -------------------------------------

/// A point of A − B and the support points it came from: w = a − b.
struct SupportPoint {
  Eigen::Vector3d w = Eigen::Vector3d::Zero(), a = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();
};

/// Support of A − B in direction d: a = sA(d), b = sB(−d).
SupportPoint minkowskiSupport(const SupportFn& a, const SupportFn& b, const Eigen::Vector3d& d);

/// Closest point to the origin of the convex hull of 1–4 points (signed-volume sub-distance). The result keeps
/// only the points whose barycentric weight is positive (the smallest face containing the closest point).
struct SubSimplex {
  int count = 0;                 ///< 1..4; 4 means the origin is inside the tetrahedron (v = 0)
  int index[4] = {0, 0, 0, 0};   ///< indices into the input
  double lambda[4] = {0, 0, 0, 0};
  Eigen::Vector3d v = Eigen::Vector3d::Zero();  ///< the closest point, Σ lambda_i p_index[i]
};
SubSimplex closestOnSimplex(const Eigen::Vector3d* points, int n);

/// Sizes used for tolerances and rounding thresholds of one query.
struct ConvexScale {
  double size = 0;      ///< diagonal of the bounding box of A − B (sum of the sizes of A and B)
  double coordMag = 0;  ///< largest |coordinate| of any support point seen (rounding is relative to it)
  double roundoff() const;  ///< absolute rounding level of a coordinate or a dot product: a few ulps of both
};

struct GjkResult {
  SupportPoint simplex[4];
  double lambda[4] = {0, 0, 0, 0};
  int count = 0;
  Eigen::Vector3d v = Eigen::Vector3d::Zero();  ///< closest point of hull(simplex) to the origin (= pointA − pointB)
  Eigen::Vector3d pointA = Eigen::Vector3d::Zero(), pointB = Eigen::Vector3d::Zero();
  double lowerBound = 0, upperBound = 0;  ///< on the signed distance
  /// upperBound minus the separating-axis gap along the final direction v: bounds the sum of the depths of
  /// pointA in A and pointB in B (each lies inside its set, at most this far from its boundary along v).
  /// +inf when the final simplex was not checked against a support along its own direction.
  double witnessGap = std::numeric_limits<double>::infinity();
  int iterations = 0;
  bool originInside = false;  ///< hull(simplex) contains the origin to working precision (overlap or touching)
  bool converged = false;     ///< upper − lower <= tolerance and witnessGap <= tolerance
};

/// The GJK loop from one starting point of A − B. lowerBound is an already-known lower bound (or −inf).
/// scale.coordMag is raised as support points are seen.
GjkResult gjk(const SupportFn& a, const SupportFn& b, const SupportPoint& start, double lowerBound, double tolerance,
              int maxIterations, ConvexScale& scale);

struct EpaResult {
  bool valid = false;         ///< a full-dimensional polytope was built (false: A − B is flat to working precision)
  bool originInside = false;  ///< the final polytope (inside A − B) contains the origin, to rounding
  /// max over tried unit n of −h_D(n): a lower bound on the signed distance, whatever the configuration.
  double signedLower = -std::numeric_limits<double>::infinity();
  /// Origin inside the polytope: −(its distance to the polytope's boundary), since the polytope lies in D.
  /// Origin just outside (contact, or GJK stopped short): the distance to the closest face, a realised pair of
  /// points of A and B. Either way an upper bound on the signed distance.
  double signedUpper = std::numeric_limits<double>::infinity();
  /// The reported signed distance, normal (A toward B; when overlapping, the way B moves) and points
  /// (pointB − pointA ≈ distance·normal). Overlap, converged: the closest face. Overlap, not converged: the best
  /// support direction (−min h_D), which approaches the truth much faster than the faces where the minimum
  /// translation direction is not unique (concentric spheres: exact at once, while faces must tile the sphere).
  double distance = 0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d pointA = Eigen::Vector3d::Zero(), pointB = Eigen::Vector3d::Zero();
  /// Bound on the sum of the depths of pointA in A and pointB in B: h_D(n) + signedUpper for the closest face
  /// (+inf when that face was not checked against a support along its normal n).
  double witnessGap = std::numeric_limits<double>::infinity();
  int iterations = 0;
  bool converged = false;  ///< signedUpper − signedLower <= tolerance and witnessGap <= tolerance
};

/// EPA seeded with points of A − B: the first `keep` are GJK's final simplex (which may hold the origin) and are
/// all used; the others (axis supports, say) are skipped when nearly duplicating one already taken.
EpaResult epa(const SupportFn& a, const SupportFn& b, const std::vector<SupportPoint>& seeds, int keep,
              double tolerance, int maxIterations, ConvexScale& scale);

}  // namespace unidist::detail
