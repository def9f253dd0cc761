#include "pairs/convex_pair.h"

#include "nurbs/convex_support.h"
#include "unidist/nurbs.h"

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

DistanceResult convexPairOfSupports(const SupportFn& supportA, const SupportFn& supportB, const QueryContext& ctx) {
  const ConvexDistance c = convexDistance(supportA, supportB, ctx.tolerance, std::min(ctx.maxIterations, kConvexIterationCap));
  DistanceResult r = fromConvex(c, "gjk-epa");
  // Certified only when the bounds meet and the witness points are proved on their surfaces.
  settleStatus(r, ctx.tolerance);
  if (!c.converged) r.status = Status::Bounded;
  return r;
}

DistanceResult convexPair(const PosedModel& a, const PosedModel& b, const QueryContext& ctx) {
  return convexPairOfSupports([&a](const Eigen::Vector3d& d) { return a.supportWorld(d); },
                              [&b](const Eigen::Vector3d& d) { return b.supportWorld(d); }, ctx);
}

bool convexSolid(const Model& m) {
  if (m.isConvex()) return true;
  const auto* nurbs = dynamic_cast<const NurbsModel*>(&m);
  return nurbs && nurbs->provedConvex();
}

SupportFn supportMapOf(const PosedModel& m) {
  const auto* nurbs = dynamic_cast<const NurbsModel*>(&m.model);
  if (!nurbs || !nurbs->provedConvex()) return [&m](const Eigen::Vector3d& d) { return m.supportWorld(d); };
  return [&m, nurbs](const Eigen::Vector3d& d) {
    return Eigen::Vector3d(m.X_WM * nurbs::convexSupport(*nurbs, m.X_WM.linear().transpose() * d));
  };
}

}  // namespace unidist::detail
