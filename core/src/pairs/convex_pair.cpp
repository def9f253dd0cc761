#include "pairs/convex_pair.h"

#include <algorithm>

namespace unidist::detail {

namespace {

// GJK/EPA converge in tens of iterations; thousands mean a degenerate overlap (coaxial, concentric) whose
// direction is not unique: stop there with honest bounds instead of spending half a second.
constexpr int kConvexIterationCap = 4000;

}  // namespace

DistanceResult fromConvex(const ConvexDistance& c, const char* method) {
  DistanceResult r;
  r.distance = c.distance;
  r.pointA = c.pointA;
  r.pointB = c.pointB;
  r.normal = c.normal;
  r.lowerBound = std::min(c.lowerBound, c.distance);
  r.upperBound = std::max(c.upperBound, c.distance);
  r.iterations = c.iterations;
  r.method = method;
  return r;
}

DistanceResult convexPair(const PosedModel& a, const PosedModel& b, const QueryContext& ctx) {
  const SupportFn supportA = [&a](const Eigen::Vector3d& d) { return a.supportWorld(d); };
  const SupportFn supportB = [&b](const Eigen::Vector3d& d) { return b.supportWorld(d); };
  const ConvexDistance c = convexDistance(supportA, supportB, ctx.tolerance, std::min(ctx.maxIterations, kConvexIterationCap));
  DistanceResult r = fromConvex(c, "gjk-epa");
  // Certified only when the bounds meet and the witness points are proved on their surfaces.
  settleStatus(r, ctx.tolerance);
  if (!c.converged) r.status = Status::Bounded;
  return r;
}

}  // namespace unidist::detail
