// The generic path for any two models (Johnson & Cohen's unified distance, made global): alternating
// projection from several starts finds a good pair fast; branch and bound over surface cells then proves
// how far the answer can be from the truth. Penetrating solids get proved bounds on the translation depth
// (the deepest surface point below, a supporting-plane escape above) and the deepest-point estimate.
#include "generic/generic_distance.h"

#include "generic/surface_search.h"
#include "pairs/analytic.h"

#include <algorithm>
#include <cmath>

namespace unidist::detail {

namespace {

// Surface branch and bound budget (field evaluations) per direction of the search.
constexpr int kSurfaceBudget = 400000;

struct DeepestPoint {
  SurfaceMinimum search;  // min over this surface of the other model's field
  bool ofA;                        // the surface searched is A's
};

}  // namespace

DistanceResult genericPair(const PosedModel& a, const PosedModel& b, const QueryContext& ctx) {
  const double tol = ctx.tolerance;
  const int stepsPerStart = std::max(1, std::min(ctx.maxIterations, 200));

  // 1. Alternating projection from several starts; keep the closest pair.
  PointPair best;
  best.gap = std::numeric_limits<double>::infinity();
  int iterations = 0;
  for (const Eigen::Vector3d& start : alternationStarts(a, b)) {
    const PointPair p = alternate(a, b, start, tol, stepsPerStart);
    iterations += p.iterations + 1;
    if (p.gap < best.gap) best = p;
  }

  // 2. Branch and bound over each surface against the other's field. A model without an inside has no
  //    field sign, so for it the search over the other surface is what the contract defines.
  const bool solidA = a.model.isSolid(), solidB = b.model.isSolid();
  std::vector<DeepestPoint> searches;
  if (solidB || !solidA)
    searches.push_back({minimizeFieldOverSurface(a, b, fieldValue(b, best.onA), best.onA, 0.5 * tol, kSurfaceBudget), true});
  if (solidA || !solidB)
    searches.push_back({minimizeFieldOverSurface(b, a, fieldValue(a, best.onB), best.onB, 0.5 * tol, kSurfaceBudget), false});
  for (const DeepestPoint& s : searches) iterations += s.search.evaluations;

  // Every search's lower bound bounds the same minimum (when separated, or for models without an inside).
  double lower = -std::numeric_limits<double>::infinity(), value = std::numeric_limits<double>::infinity();
  const DeepestPoint* deepest = &searches.front();
  for (const DeepestPoint& s : searches) {
    lower = std::max(lower, s.search.lowerBound);
    if (s.search.value < value) {
      value = s.search.value;
      deepest = &s;
    }
  }
  // Two solids are proved apart only when neither surface can reach into the other (this also rules out
  // containment, where one surface lies wholly inside the other solid).
  bool provedApart = true;
  for (const DeepestPoint& s : searches) provedApart = provedApart && s.search.lowerBound > 0;

  DistanceResult r;
  r.iterations = iterations;
  r.method = "generic-alternating+surface-bnb";
  // Witness pair from the deepest/closest surface point and its closest point on the other model.
  const PosedModel& fieldOwner = deepest->ofA ? b : a;
  const SurfacePoint onField = fieldOwner.closestWorld(deepest->search.point);
  Eigen::Vector3d pA = deepest->ofA ? deepest->search.point : onField.point;
  Eigen::Vector3d pB = deepest->ofA ? onField.point : deepest->search.point;
  if (value >= 0 && best.gap < value) {  // alternation found a closer pair than the sampled search
    value = best.gap;
    pA = best.onA;
    pB = best.onB;
  }
  r.pointA = pA;
  r.pointB = pB;

  if (value >= 0 || !(solidA && solidB)) {
    // Separation (or the contract's min over a model without an inside, possibly negative).
    r.distance = value;
    const Eigen::Vector3d gapVector = pB - pA;
    const double gapNorm = gapVector.norm();
    if (value >= 0) {
      r.normal = gapNorm > 0 ? Eigen::Vector3d(gapVector / gapNorm)
                             : Eigen::Vector3d(deepest->ofA ? -onField.normal : onField.normal);
      r.distance = gapNorm;
    } else {
      // A point of the model without an inside lies in the solid: it leaves along the solid's normal.
      r.normal = deepest->ofA ? Eigen::Vector3d(-onField.normal) : onField.normal;
      r.distance = value;
    }
    r.upperBound = r.distance;
    double proved = lower;
    if (solidA && solidB) {
      proved = supportGapLowerBound(a, b, r.normal);
      if (provedApart) proved = std::max(proved, lower);
    }
    r.lowerBound = std::min(proved, r.distance);
    settleStatus(r, tol);
    return r;
  }

  // 3. Two solids overlap. Proved: the deepest surface point must travel at least its depth, so
  //    distance <= value; a supporting-plane gap along any direction bounds the depth from the other side.
  r.distance = value;
  r.normal = deepest->ofA ? Eigen::Vector3d(-onField.normal) : onField.normal;
  r.upperBound = value;
  double lowerSd = -std::numeric_limits<double>::infinity();
  std::vector<Eigen::Vector3d> directions = {r.normal};
  for (int i = 0; i < 3; ++i) {
    directions.push_back(Eigen::Vector3d::Unit(i));
    directions.push_back(-Eigen::Vector3d::Unit(i));
  }
  for (const Eigen::Vector3d& u : directions) lowerSd = std::max(lowerSd, supportGapLowerBound(a, b, u));
  r.lowerBound = std::min(lowerSd, r.distance);
  settleStatus(r, tol);
  return r;
}

}  // namespace unidist::detail
