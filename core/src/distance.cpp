// Public entry of the distance query: checks the input, settles the tolerance, dispatches the pair and
// applies inflation (a swept sphere around each model).
#include "unidist/distance.h"

#include "dispatch.h"
#include "generic/generic_distance.h"
#include "generic/pair_polish.h"
#include "pairs/analytic.h"

#include <algorithm>
#include <cmath>

namespace unidist {
namespace {

/// First tolerance of an overlap test, relative to the larger posed bounding-box diagonal.
constexpr double kOverlapCoarseTolerance = 1e-3;

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

/// The larger posed bounding-box diagonal (1 when both models are unbounded): what default tolerances scale with.
double sizeOfPair(const Model& a, const Eigen::Isometry3d& X_WA, const Model& b, const Eigen::Isometry3d& X_WB) {
  const double diagonal = std::max(worldDiagonal(a, X_WA), worldDiagonal(b, X_WB));
  return diagonal > 0 ? diagonal : 1.0;
}

/// Magnitude of the coordinates involved, for rounding-level tolerances.
double coordinateScale(const Model& a, const Eigen::Isometry3d& X_WA, const Model& b, const Eigen::Isometry3d& X_WB) {
  return X_WA.translation().norm() + X_WB.translation().norm() + worldDiagonal(a, X_WA) + worldDiagonal(b, X_WB);
}

/// A cheap proved lower bound on |distance| of separated models: the gap between their bounding spheres (0 when
/// they meet or a model is unbounded). What a relative tolerance may be applied to.
double provedSeparation(const Model& a, const Eigen::Isometry3d& X_WA, const Model& b, const Eigen::Isometry3d& X_WB) {
  if (!a.localBounds().bounded() || !b.localBounds().bounded()) return 0.0;
  const BoundingSphere sa = a.localBoundingSphere(), sb = b.localBoundingSphere();
  const double gap = (X_WA * sa.center - X_WB * sb.center).norm() - sa.radius - sb.radius;
  return std::max(gap, 0.0);
}

detail::QueryContext settle(const Model& a, const Eigen::Isometry3d& X_WA, const Model& b,
                            const Eigen::Isometry3d& X_WB, const DistanceOptions& options) {
  if (std::isnan(options.tolerance) || std::isinf(options.tolerance))
    throw InputError("tolerance must be finite");
  for (double inflate : {options.inflateA, options.inflateB})
    if (!std::isfinite(inflate) || inflate < 0) throw InputError("inflation radius must be finite and >= 0");
  if (const char* why = invalidDialSetting(options)) throw InputError(why);
  double tol = options.tolerance < 0 ? defaultTolerance(a, X_WA, b, X_WB) : options.tolerance;
  tol = std::max(tol, options.relativeTolerance * provedSeparation(a, X_WA, b, X_WB));
  // "0" asks for what double precision allows: a few ulps of the coordinates involved.
  const double floor = 64 * std::numeric_limits<double>::epsilon() * std::max(coordinateScale(a, X_WA, b, X_WB), 1e-300);
  detail::QueryContext ctx{std::max(tol, floor), options.maxIterations};
  ctx.overlapVerdictOnly = options.compute != Compute::SignedDistance;
  return ctx;
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

const char* toString(Compute c) {
  switch (c) {
    case Compute::Overlap: return "overlap";
    case Compute::Separation: return "separation";
    case Compute::SignedDistance: return "signed-distance";
  }
  return "?";
}

double defaultTolerance(const Model& a, const Eigen::Isometry3d& X_WA, const Model& b, const Eigen::Isometry3d& X_WB) {
  return 1e-9 * sizeOfPair(a, X_WA, b, X_WB);
}

namespace {

/// Checks, settles the tolerance, runs `routine` on the posed pair and applies inflation.
DistanceResult answer(detail::PairFn routine, const Model& a, const Eigen::Isometry3d& X_WA, const Model& b,
                      const Eigen::Isometry3d& X_WB, const DistanceOptions& options) {
  requireValidPose(X_WA, "A");
  requireValidPose(X_WB, "B");
  const detail::QueryContext ctx = settle(a, X_WA, b, X_WB, options);
  const detail::PosedModel pa{a, X_WA}, pb{b, X_WB};
  bool measured = false;  // the last run was a full query (no verdict-only shortcut)
  const auto run = [&](detail::QueryContext c) {
    DistanceResult r = routine(pa, pb, c);
    // A verdict-only routine proves an overlap (upperBound <= 0) or that the models are apart (lowerBound > 0,
    // the distance not measured to the tolerance); when it did neither (surfaces within its tolerance, or its
    // search ran out), only the full query settles it.
    if (c.overlapVerdictOnly && !(r.upperBound <= 0) && !(r.lowerBound > 0)) {
      c.overlapVerdictOnly = false;
      r = routine(pa, pb, c);
    }
    measured = !c.overlapVerdictOnly;
    if (measured) detail::polishSeparation(pa, pb, r, c.tolerance);
    inflate(r, pa, pb, options.inflateA, options.inflateB, c.tolerance);
    return r;
  };
  if (options.compute == Compute::SignedDistance) return run(ctx);
  if (options.compute == Compute::Separation) {
    // The verdict first: an overlap is left unmeasured; models proved apart are then measured in full.
    DistanceResult r = run(ctx);
    if (r.upperBound <= 0 || measured) return r;
    detail::QueryContext full = ctx;
    full.overlapVerdictOnly = false;
    return run(full);
  }
  // A verdict needs only the sign: a coarse pass decides every pair that is not nearly touching; the requested
  // tolerance is spent only on the rest.
  const auto decided = [](const DistanceResult& r) { return r.lowerBound > 0 || r.upperBound <= 0; };
  detail::QueryContext coarse = ctx;
  coarse.tolerance = std::max(ctx.tolerance, kOverlapCoarseTolerance * sizeOfPair(a, X_WA, b, X_WB));
  if (coarse.tolerance > ctx.tolerance) {
    DistanceResult r = run(coarse);
    if (decided(r)) {
      r.status = Status::Certified;  // the verdict is proved, which is all that was asked
      return r;
    }
  }
  DistanceResult r = run(ctx);
  if (decided(r)) r.status = Status::Certified;
  return r;
}

/// answer() on the models' stand-ins at the requested levels of detail, its bounds widened by their deviations
/// so that they hold for the models themselves. The stand-ins are queried to what is left of the tolerance once
/// the deviations are spent (to about the deviation when nothing is left: more would be wasted).
DistanceResult answerAtDetail(detail::PairFn routine, const Model& a, const Eigen::Isometry3d& X_WA, const Model& b,
                              const Eigen::Isometry3d& X_WB, const DistanceOptions& options) {
  if (options.detailA == 0 && options.detailB == 0) return answer(routine, a, X_WA, b, X_WB, options);
  // atDetail checks the levels; answer() checks everything else.
  const StandIn sa = a.atDetail(options.detailA), sb = b.atDetail(options.detailB);
  const double deviation = sa.deviation + sb.deviation;
  if (deviation == 0) return answer(routine, *sa.model, X_WA, *sb.model, X_WB, options);
  if (!std::isfinite(options.tolerance)) throw InputError("tolerance must be finite");
  const double tolerance = options.tolerance < 0 ? defaultTolerance(a, X_WA, b, X_WB) : options.tolerance;
  DistanceOptions inner = options;
  inner.tolerance = tolerance > 2.2 * deviation ? tolerance - 2 * deviation : std::max(tolerance, deviation);
  DistanceResult r = answer(routine, *sa.model, X_WA, *sb.model, X_WB, inner);
  r.lowerBound -= deviation;
  r.upperBound += deviation;
  if (options.compute == Compute::Overlap)
    r.status = r.lowerBound > 0 || r.upperBound <= 0 ? Status::Certified : Status::Bounded;
  else
    detail::settleStatus(r, tolerance);
  return r;
}

}  // namespace

DistanceResult distance(const Model& a, const Eigen::Isometry3d& X_WA, const Model& b, const Eigen::Isometry3d& X_WB,
                        const DistanceOptions& options) {
  return answerAtDetail(&detail::dispatchPair, a, X_WA, b, X_WB, options);
}

DistanceResult genericDistance(const Model& a, const Eigen::Isometry3d& X_WA, const Model& b,
                               const Eigen::Isometry3d& X_WB, const DistanceOptions& options) {
  return answerAtDetail(&detail::genericPair, a, X_WA, b, X_WB, options);
}

}  // namespace unidist
