// The generic path for any two models (Johnson & Cohen's unified distance, made global): alternating
// projection from several starts finds a good pair fast; branch and bound over surface cells then proves
// how far the answer can be from the truth. Penetrating solids go on to the global translation-depth search
// (generic/translation_depth.h), seeded with the deepest surface point found here.
#include "generic/generic_distance.h"

#include "generic/surface_search.h"
#include "generic/translation_depth.h"
#include "pairs/analytic.h"

#include <algorithm>
#include <cmath>

namespace unidist::detail {

namespace {

// Surface branch and bound budget (field evaluations) per direction of the search.
constexpr int kSurfaceBudget = 400000;
// Evaluations a surface search may still spend after it has proved two solids overlap.
constexpr int kSeedBudget = 1000;
// Evaluations per surface for a separation test of the depth search.
constexpr int kVerdictBudget = 20000;

/// A proved lower bound from planes that separate the two models, tried along the alternation's gap and both
/// surfaces' normals at its points (either sign: an open surface's normal may face either way). A touching
/// contact that such a plane separates — a sheet on a ball, a ball on a face — is certified here at once, where
/// the first-order branch and bound cannot close on it (a tangent contact: 400,000 point queries, seconds).
double separatingPlaneBound(const PosedModel& a, const PosedModel& b, const Eigen::Vector3d& onA,
                            const Eigen::Vector3d& onB, Eigen::Vector3d& direction) {
  std::vector<Eigen::Vector3d> directions;
  const Eigen::Vector3d gap = onB - onA;
  if (gap.norm() > 0) directions.push_back(gap.normalized());
  for (const Eigen::Vector3d& n : {a.closestWorld(onA).normal, b.closestWorld(onB).normal})
    if (n.allFinite() && n.norm() > 0.5) {
      directions.push_back(n);
      directions.push_back(-n);
    }
  double best = -std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& u : directions) {
    const double bound = supportGapLowerBound(a, b, u);
    if (bound > best) best = bound, direction = u;
  }
  return best;
}

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

  // 1b. Models apart or touching that a plane separates: proved at once.
  if (std::isfinite(best.gap) && a.model.localBounds().bounded() && b.model.localBounds().bounded()) {
    Eigen::Vector3d u = Eigen::Vector3d::UnitZ();
    const double lower = separatingPlaneBound(a, b, best.onA, best.onB, u);
    // The models' extreme points along the separating direction touch across the plane: a closer pair than the
    // alternation's where its projections converge slowly (a NURBS pole).
    if (lower > -std::numeric_limits<double>::infinity())
      for (const bool fromB : {true, false}) {
        const Eigen::Vector3d extreme = fromB ? b.supportWorld(-u) : a.supportWorld(u);
        const Eigen::Vector3d other = (fromB ? a : b).closestWorld(extreme).point;
        const double gap = (extreme - other).norm();
        if (gap < best.gap) {
          best.gap = gap;
          best.onA = fromB ? other : extreme;
          best.onB = fromB ? extreme : other;
        }
      }
    if (best.gap - lower <= tol) {
      DistanceResult r;
      r.iterations = iterations;
      r.method = "generic-alternating+separating-plane";
      r.pointA = best.onA;
      r.pointB = best.onB;
      r.distance = best.gap;
      r.normal = best.gap > 0 ? Eigen::Vector3d((best.onB - best.onA) / best.gap) : b.closestWorld(best.onB).normal;
      r.upperBound = best.gap;
      r.lowerBound = std::min(lower, best.gap);
      settleStatus(r, tol);
      return r;
    }
  }

  // 2. Branch and bound over each surface against the other's field. A model without an inside has no
  //    field sign, so for it the search over the other surface is what the contract defines.
  const bool solidA = a.model.isSolid(), solidB = b.model.isSolid();
  std::vector<DeepestPoint> searches;
  //    When both are solids a negative value proves an overlap, and the deepest point found then only seeds
  //    the depth search: a short extra budget suffices.
  const int onceNegative = solidA && solidB ? kSeedBudget : kSurfaceBudget;
  // A separation test for the depth search only needs a sign: an exhausted budget just counts as "not proved".
  const int budget = ctx.overlapVerdictOnly ? kVerdictBudget : kSurfaceBudget;
  auto searchSurfaceOf = [&](bool ofA, int surfaceBudget) {
    const PosedModel& surface = ofA ? a : b;
    const PosedModel& field = ofA ? b : a;
    const Eigen::Vector3d& hint = ofA ? best.onA : best.onB;
    searches.push_back(
        {minimizeFieldOverSurface(surface, field, fieldValue(field, hint), hint, 0.5 * tol, surfaceBudget, onceNegative),
         ofA});
  };
  //    Once one search has proved two solids overlap, the other only seeds the depth search (a verdict needs
  //    nothing more): it gets the seed budget. A contained model is the smaller one and its surface proves the
  //    overlap at once, so the smaller solid's surface goes first; the other surface never reaches a negative
  //    value and would spend the whole budget (400,000 point queries: 25 s for a NURBS box around a NURBS ball).
  bool order[2] = {true, false};  // search A's surface first
  if (solidA && solidB && b.model.localBoundingSphere().radius < a.model.localBoundingSphere().radius)
    std::swap(order[0], order[1]);
  for (const bool ofA : order) {
    if (!(ofA ? (solidB || !solidA) : (solidA || !solidB))) continue;
    const bool overlapProved = solidA && solidB && !searches.empty() && searches.front().search.value < 0;
    if (overlapProved && ctx.overlapVerdictOnly) return overlapVerdict();
    searchSurfaceOf(ofA, overlapProved ? kSeedBudget : budget);
  }
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
  if (ctx.overlapVerdictOnly && solidA && solidB && value < 0) return overlapVerdict();

  DistanceResult r;
  r.iterations = iterations;
  r.method = "generic-alternating+surface-bnb";
  // Witness pair from the deepest/closest surface point and its closest point on the other model.
  const PosedModel& fieldOwner = deepest->ofA ? b : a;
  const SurfacePoint onField = fieldOwner.closestWorld(deepest->search.point);
  // The other model's normal there, turned to point from A toward B (the way B leaves when overlapping).
  const Eigen::Vector3d awayFromA = deepest->ofA ? Eigen::Vector3d(-onField.normal) : onField.normal;
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
      r.normal = gapNorm > 0 ? Eigen::Vector3d(gapVector / gapNorm) : awayFromA;
      r.distance = gapNorm;
    } else {
      // A point of the model without an inside lies in the solid: it leaves along the solid's normal.
      r.normal = awayFromA;
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

  // 3. Two solids overlap (a separation test stopped above): the global translation depth, bracketed by
  //    proved bounds.
  OverlapSeed seed;
  // The deepest surface point must travel at least its depth (less the point query's error: its distance is realised).
  seed.provedDepth = std::max(0.0, -value - onField.error);
  seed.deepPoint = deepest->search.point;
  seed.direction = awayFromA;
  deepenSeed(a, b, tol, seed);
  addPlaneEscapes(a, b, seed);
  DistanceResult depth = translationalDepth(a, b, ctx, seed);
  depth.iterations += iterations;
  return depth;
}

}  // namespace unidist::detail
