// Public entry of the distance query: checks the input, settles the tolerance, dispatches the pair and
// applies inflation (a swept sphere around each model).
#include "unidist/distance.h"

#include "dispatch.h"
#include "generic/generic_distance.h"
#include "pairs/analytic.h"

#include <algorithm>
#include <cmath>

namespace unidist {
namespace {

void requireValidPose(const Eigen::Isometry3d& X, const char* which) {
  if (!X.matrix().allFinite()) throw InputError(std::string("pose of ") + which + " has a NaN or infinite entry");
  const Eigen::Matrix3d R = X.linear();
  // A pose is rigid: an orthonormal rotation, up to what rounding of a normalised quaternion leaves.
  if (!(R.transpose() * R).isApprox(Eigen::Matrix3d::Identity(), 1e-9) || R.determinant() < 0)
    throw InputError(std::string("pose of ") + which + " is not a rigid motion");
}

double worldDiagonal(const Model& m, const Eigen::Isometry3d& X) {
  const Aabb box = m.localBounds();
  return box.bounded() ? box.transformed(X).diagonal() : 0.0;
}

/// Magnitude of the coordinates involved, for rounding-level tolerances.
double coordinateScale(const Model& a, const Eigen::Isometry3d& X_WA, const Model& b, const Eigen::Isometry3d& X_WB) {
  return X_WA.translation().norm() + X_WB.translation().norm() + worldDiagonal(a, X_WA) + worldDiagonal(b, X_WB);
}

detail::QueryContext settle(const Model& a, const Eigen::Isometry3d& X_WA, const Model& b,
                            const Eigen::Isometry3d& X_WB, const DistanceOptions& options) {
  if (std::isnan(options.tolerance) || std::isinf(options.tolerance))
    throw InputError("tolerance must be finite");
  for (double inflate : {options.inflateA, options.inflateB})
    if (!std::isfinite(inflate) || inflate < 0) throw InputError("inflation radius must be finite and >= 0");
  if (options.maxIterations < 1) throw InputError("maxIterations must be >= 1");
  double tol = options.tolerance < 0 ? defaultTolerance(a, X_WA, b, X_WB) : options.tolerance;
  // "0" asks for what double precision allows: a few ulps of the coordinates involved.
  const double floor = 64 * std::numeric_limits<double>::epsilon() * std::max(coordinateScale(a, X_WA, b, X_WB), 1e-300);
  return {std::max(tol, floor), options.maxIterations};
}

/// Grows A and B by balls. Exact for convex pairs (the Minkowski difference grows by a ball) and for a
/// separation that survives the growth; otherwise only the upper bound carries over and the lower bound
/// comes from supporting planes.
void inflate(DistanceResult& r, const detail::PosedModel& a, const detail::PosedModel& b, double ra, double rb,
             double tolerance) {
  const double grow = ra + rb;
  if (grow == 0) return;
  const bool exactShift = (a.model.isConvex() && b.model.isConvex()) || r.lowerBound - grow >= 0;
  r.distance -= grow;
  r.pointA += ra * r.normal;
  r.pointB -= rb * r.normal;
  r.upperBound -= grow;
  if (exactShift) {
    r.lowerBound -= grow;
  } else {
    double lower = detail::supportGapLowerBound(a, b, r.normal);
    for (int i = 0; i < 3; ++i)
      for (double s : {1.0, -1.0}) lower = std::max(lower, detail::supportGapLowerBound(a, b, s * Eigen::Vector3d::Unit(i)));
    r.lowerBound = std::min(lower - grow, r.distance);
  }
  detail::settleStatus(r, tolerance);
}

}  // namespace

double defaultTolerance(const Model& a, const Eigen::Isometry3d& X_WA, const Model& b, const Eigen::Isometry3d& X_WB) {
  const double diagonal = std::max(worldDiagonal(a, X_WA), worldDiagonal(b, X_WB));
  return 1e-9 * (diagonal > 0 ? diagonal : 1.0);
}

namespace {

/// Checks, settles the tolerance, runs `routine` on the posed pair and applies inflation.
DistanceResult answer(detail::PairFn routine, const Model& a, const Eigen::Isometry3d& X_WA, const Model& b,
                      const Eigen::Isometry3d& X_WB, const DistanceOptions& options) {
  requireValidPose(X_WA, "A");
  requireValidPose(X_WB, "B");
  const detail::QueryContext ctx = settle(a, X_WA, b, X_WB, options);
  const detail::PosedModel pa{a, X_WA}, pb{b, X_WB};
  DistanceResult r = routine(pa, pb, ctx);
  inflate(r, pa, pb, options.inflateA, options.inflateB, ctx.tolerance);
  return r;
}

}  // namespace

DistanceResult distance(const Model& a, const Eigen::Isometry3d& X_WA, const Model& b, const Eigen::Isometry3d& X_WB,
                        const DistanceOptions& options) {
  return answer(&detail::dispatchPair, a, X_WA, b, X_WB, options);
}

DistanceResult genericDistance(const Model& a, const Eigen::Isometry3d& X_WA, const Model& b,
                               const Eigen::Isometry3d& X_WB, const DistanceOptions& options) {
  return answer(&detail::genericPair, a, X_WA, b, X_WB, options);
}

}  // namespace unidist
