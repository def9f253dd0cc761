#include "pairs/nurbs_convex.h"

#include "convex/gjk.h"
#include "generic/translation_depth.h"
#include "nurbs/patch_tree.h"
#include "pairs/analytic.h"
#include "pairs/convex_pair.h"
#include "unidist/nurbs.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <queue>
#include <vector>

namespace unidist::detail {

namespace {

// GJK on a control-point hull and a primitive converges in a few iterations; the cap guards degenerate input.
constexpr int kNodeGjkCap = 200;
// Subdivision stops here (node size ~2^-40 of a patch): rounding, not the bound, limits deeper nodes.
constexpr int kMaxDepth = 40;
// Nodes popped before the search reports a bounded answer.
constexpr int kNodeBudget = 200000;

struct OpenNode {
  double lower;
  const nurbs::PatchNode* node;
  Eigen::Vector3d witnessB;  // GJK's closest point of B to the node's hull (A's frame)
  bool hullApart;
  bool operator>(const OpenNode& o) const { return lower > o.lower; }
};

struct Search {
  double best = std::numeric_limits<double>::infinity();  // realised: signed distance of a surface point to B
  Eigen::Vector3d pA = Eigen::Vector3d::Zero(), pB = Eigen::Vector3d::Zero(), nB = Eigen::Vector3d::UnitZ();
  double lowerOfClosed = std::numeric_limits<double>::infinity();  // nodes not split further (depth cap)
  double lowerOpen = std::numeric_limits<double>::infinity();
  double lowerPlane = -std::numeric_limits<double>::infinity();  // the supporting planes' bound, where tried
  int iterations = 0;
  /// The proved lower bound: the open and closed nodes', or the planes' where it is higher (it holds for all).
  double lower() const { return std::max(lowerPlane, std::min(lowerOpen, lowerOfClosed)); }
};

class NodeBounds {
 public:
  NodeBounds(const PosedModel& bInA, double tolerance)
      : bInA_(bInA), tolerance_(tolerance),
        supportB_([&bInA](const Eigen::Vector3d& d) { return bInA.supportWorld(d); }) {}

  /// Proved lower bound on the distance from the subpatch to B: GJK on its control-point hull, less the
  /// rounding of the subdivided net (the same 256 ulps the node's ball is widened by).
  double lower(const nurbs::PatchNode& n, int& iterations) {
    // A node whose ball centre lies in B has its hull overlapping B: skip GJK (it would run EPA) and use the
    // first-order ball bound (the signed distance is 1-Lipschitz).
    const double atCentre = bInA_.closestWorld(n.ball.center).signedDistance;
    if (atCentre <= 0) {
      lastHullApart_ = false;
      return atCentre - n.ball.radius;
    }
    // A hull overlapping B bounds its surface points' signed distance by the hulls' separating-axis bound as
    // well as by their depth: EPA is not run (against a thin B — a plate 1e-7 thick — it dominated the
    // overlap search: 12 s for one depth query, 3 s without).
    const ConvexDistance c =
        convexDistance(supportOfPointSet(n.points), supportB_, 0.25 * tolerance_, kNodeGjkCap, false);
    iterations += c.iterations;
    lastWitnessB_ = c.pointB;
    lastHullApart_ = c.distance > 0;
    const double margin = 256 * std::numeric_limits<double>::epsilon() * (n.ball.center.norm() + n.ball.radius);
    return std::min(c.lowerBound, c.distance) - margin;
  }
  const Eigen::Vector3d& lastWitnessB() const { return lastWitnessB_; }
  bool lastHullApart() const { return lastHullApart_; }

  /// Measures a realised surface point against B; keeps the best.
  void measure(const Eigen::Vector3d& onA, Search& s) const {
    const SurfacePoint q = bInA_.closestWorld(onA);
    if (q.signedDistance < s.best) {
      s.best = q.signedDistance;
      s.pA = onA;
      s.pB = q.point;
      s.nB = q.normal;
    }
  }

 private:
  const PosedModel& bInA_;
  double tolerance_;
  SupportFn supportB_;
  Eigen::Vector3d lastWitnessB_ = Eigen::Vector3d::Zero();
  bool lastHullApart_ = false;
};

/// Best-first search in A's frame; stops once a surface point of A is inside B (the solids overlap).
Search closestSubpatch(const NurbsModel& m, const PosedModel& bInA, double tolerance) {
  NodeBounds bounds(bInA, tolerance);
  Search s;
  std::vector<std::unique_ptr<nurbs::PatchNode>> arena;
  std::priority_queue<OpenNode, std::vector<OpenNode>, std::greater<OpenNode>> open;
  auto visit = [&](const nurbs::PatchNode* n) {
    for (const Eigen::Vector3d& c : n->corners) bounds.measure(c, s);
    const double lower = bounds.lower(*n, s.iterations);
    open.push({lower, n, bounds.lastWitnessB(), bounds.lastHullApart()});
  };
  for (const auto& root : m.forest().roots) visit(root.get());
  int popped = 0;
  bool planeTried = false;
  const PosedModel aInA{m, Eigen::Isometry3d::Identity()};
  while (!open.empty()) {
    const OpenNode top = open.top();
    if (top.lower >= s.best - 0.5 * tolerance || s.best < 0 || popped >= kNodeBudget) break;
    // Touching: the supporting planes across the contact normal may settle every node at once. A torus resting on
    // a box touches it along a circle, which the hulls' bounds would refine node by node (1.1 s, then bounded).
    if (!planeTried && s.best <= 0.5 * tolerance) {
      planeTried = true;
      s.lowerPlane = supportGapLowerBound(aInA, bInA, -s.nB);
      if (s.lowerPlane >= s.best - 0.5 * tolerance) break;
    }
    open.pop();
    ++popped;
    ++s.iterations;
    if (top.node->depth >= kMaxDepth) {
      s.lowerOfClosed = std::min(s.lowerOfClosed, top.lower);
      continue;
    }
    // A second-order upper bound: the surface point closest to B's witness for this hull.
    if (top.hullApart) bounds.measure(m.closestPoint(top.witnessB).point, s);
    for (const nurbs::PatchNode* c : m.forest().children(*top.node, arena)) visit(c);
  }
  if (!open.empty()) s.lowerOpen = open.top().lower;
  return s;
}

}  // namespace

DistanceResult nurbsConvex(const PosedModel& a, const PosedModel& b, const QueryContext& ctx) {
  const auto& m = static_cast<const NurbsModel&>(a.model);
  const PosedModel bInA{b.model, a.X_WM.inverse() * b.X_WM};
  // Containment of B in A (any point of B) or of A in B (any point of A) first: it proves the overlap, which
  // apart surfaces have only then, and it spares the surface search (a sphere centred in a NURBS sphere: 20 s).
  const Eigen::Vector3d supportOfB = bInA.supportWorld(Eigen::Vector3d::UnitX());
  const Eigen::Vector3d& cornerOfA = m.forest().roots.front()->corners[0];
  std::optional<Eigen::Vector3d> inside;  // a point of one inside the other (A's frame)
  if (insideSolid(m, supportOfB)) inside = supportOfB;
  else if (insideSolid(b.model, bInA.toLocal(cornerOfA))) inside = cornerOfA;
  const bool contained = inside.has_value();
  const Search s = contained ? Search{} : closestSubpatch(m, bInA, ctx.tolerance);
  const bool meet = s.best < 0;
  if (meet || contained) {
    if (ctx.overlapVerdictOnly) return overlapVerdict();
    if (convexSolid(m)) {  // two convex solids (B is): the depth is their support functions' (GJK/EPA)
      DistanceResult r = convexPairOfSupports(supportMapOf(a), supportMapOf(b), ctx);
      r.method = "gjk-epa-proved-convex";
      return r;
    }
    // A point of one inside the other was found (a surface point of A inside B, or the containment test's point):
    // the escape at the deepest point near it settles a shallow overlap.
    if (std::optional<DistanceResult> r = shallowDepth(a, b, ctx, a.toWorld(meet ? s.pA : *inside))) {
      r->iterations += s.iterations;
      capAtContact(*r, ctx.tolerance);
      return *r;
    }
    OverlapSeed seed = seedOverlap(a, b, ctx);
    deepenSeed(a, b, ctx.tolerance, seed);
    DistanceResult r = translationalDepth(a, b, ctx, seed);
    r.iterations += s.iterations;
    capAtContact(r, ctx.tolerance);  // the interiors meet: distance <= 0 is proved
    return r;
  }
  return separationFromPoints(a, s.pA, s.pB, -s.nB, s.lower(), s.iterations,
                              "nurbs-convex-tree-gjk", ctx.tolerance);
}

}  // namespace unidist::detail
