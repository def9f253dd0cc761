#include "pairs/nurbs_nurbs.h"

#include "convex/gjk.h"
#include "generic/generic_distance.h"
#include "nurbs/patch_tree.h"
#include "unidist/nurbs.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <vector>

namespace unidist::detail {

namespace {

constexpr int kHullGjkCap = 200;  // GJK on two small hulls converges in a few iterations; a guard only
constexpr int kMaxDepth = 40;     // beyond this, rounding and not the bound limits the nodes
// Pairs popped before giving up on proving a separation here (then the generic routine answers). Enough for
// a point contact at 1e-12 (tens of pairs per level); small enough that an intersection costs little.
constexpr int kPairBudget = 20000;
constexpr int kPolishSteps = 20;  // alternating projections; each step improves the gap or stops

using Node = nurbs::PatchNode;

struct OpenPair {
  double lower;
  const Node* a;
  const Node* b;
  Eigen::Vector3d wA, wB;  // GJK's closest hull points (A's frame)
  bool operator>(const OpenPair& o) const { return lower > o.lower; }
};

class PairSearch {
 public:
  PairSearch(const NurbsModel& a, const NurbsModel& b, const Eigen::Isometry3d& X_AB, double tolerance)
      : a_(a), b_(b), X_AB_(X_AB), X_BA_(X_AB.inverse()), tolerance_(tolerance) {}

  /// Runs the search; true when it finished (the bounds met) within the budget.
  bool run() {
    for (const auto& ra : a_.forest().roots)
      for (const auto& rb : b_.forest().roots)
        for (const Eigen::Vector3d& ca : ra->corners)
          for (const Eigen::Vector3d& cb : rb->corners) offer(ca, X_AB_ * cb);
    for (const auto& ra : a_.forest().roots)
      for (const auto& rb : b_.forest().roots) visit(ra.get(), rb.get());
    int popped = 0;
    while (!open_.empty()) {
      const OpenPair top = open_.top();
      if (top.lower >= best_ - 0.5 * tolerance_) return true;
      // Surfaces within the tolerance may cross: proving them apart is not this search's job.
      if (best_ <= 0.5 * tolerance_ || popped >= kPairBudget) return false;
      open_.pop();
      ++popped;
      ++iterations_;
      // Realised pair near the hulls' witnesses: second order in the node size.
      const Eigen::Vector3d pA = a_.closestPoint(top.wA).point;
      const Eigen::Vector3d pB = X_AB_ * b_.closestPoint(X_BA_ * top.wB).point;
      offer(pA, pB);
      const bool splitA = top.a->ball.radius >= top.b->ball.radius;
      const Node* n = splitA ? top.a : top.b;
      if (n->depth >= kMaxDepth) {
        lowerOfClosed_ = std::min(lowerOfClosed_, top.lower);
        continue;
      }
      for (const Node* c : (splitA ? a_.forest() : b_.forest()).children(*n, arena_))
        splitA ? visit(c, top.b) : visit(top.a, c);
    }
    return true;
  }

  /// Alternating projection from the best pair: the search only bounds the gap, and near a smooth contact a
  /// pair within the tolerance of it can still point a little askew; the projections straighten it (every
  /// pair kept is realised, so the upper bound stays proved).
  void polish() {
    for (int k = 0; k < kPolishSteps; ++k) {
      const Eigen::Vector3d pA = a_.closestPoint(pB_).point;
      const Eigen::Vector3d pB = X_AB_ * b_.closestPoint(X_BA_ * pA).point;
      const double before = best_;
      offer(pA, pB);
      if (!(best_ < before)) break;
    }
  }

  double best() const { return best_; }
  double lower() const {
    const double open = open_.empty() ? std::numeric_limits<double>::infinity() : open_.top().lower;
    return std::min({open, lowerOfClosed_, lowerOfPruned_, best_});
  }
  const Eigen::Vector3d& pointA() const { return pA_; }
  const Eigen::Vector3d& pointB() const { return pB_; }
  int iterations() const { return iterations_; }

 private:
  void offer(const Eigen::Vector3d& pA, const Eigen::Vector3d& pB) {
    const double d = (pB - pA).norm();
    if (d < best_) {
      best_ = d;
      pA_ = pA;
      pB_ = pB;
    }
  }

  void visit(const Node* na, const Node* nb) {
    const Eigen::Vector3d cb = X_AB_ * nb->ball.center;
    // Rounding of the subdivided nets: the same 256 ulps the nodes' balls are widened by.
    const double eps = 256 * std::numeric_limits<double>::epsilon();
    const double margin = eps * (na->ball.center.norm() + na->ball.radius + cb.norm() + nb->ball.radius);
    // Balls first: a pair they already prune needs no GJK.
    const double byBalls = (cb - na->ball.center).norm() - na->ball.radius - nb->ball.radius - margin;
    if (byBalls >= best_ - 0.5 * tolerance_) {
      lowerOfPruned_ = std::min(lowerOfPruned_, byBalls);
      return;
    }
    hullA_.clear();
    hullB_.clear();
    for (const Eigen::Vector4d& h : na->net.net) hullA_.push_back(h.head<3>() / h[3]);
    for (const Eigen::Vector4d& h : nb->net.net) hullB_.push_back(X_AB_ * Eigen::Vector3d(h.head<3>() / h[3]));
    const ConvexDistance c = convexDistance(supportOf(hullA_), supportOf(hullB_), 0.25 * tolerance_, kHullGjkCap);
    iterations_ += c.iterations;
    const double lower = std::min(c.lowerBound, c.distance) - margin;
    if (lower >= best_ - 0.5 * tolerance_) {
      lowerOfPruned_ = std::min(lowerOfPruned_, lower);
      return;
    }
    open_.push({lower, na, nb, c.pointA, c.pointB});
  }

  static SupportFn supportOf(const std::vector<Eigen::Vector3d>& points) {
    return [&points](const Eigen::Vector3d& d) {
      std::size_t k = 0;
      double top = -std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < points.size(); ++i)
        if (const double v = d.dot(points[i]); v > top) top = v, k = i;
      return points[k];
    };
  }

  const NurbsModel& a_;
  const NurbsModel& b_;
  Eigen::Isometry3d X_AB_, X_BA_;
  double tolerance_;
  double best_ = std::numeric_limits<double>::infinity();
  double lowerOfClosed_ = std::numeric_limits<double>::infinity();  // pairs at the depth cap
  double lowerOfPruned_ = std::numeric_limits<double>::infinity();  // pairs dropped on arrival
  Eigen::Vector3d pA_ = Eigen::Vector3d::Zero(), pB_ = Eigen::Vector3d::Zero();
  int iterations_ = 0;
  std::vector<Eigen::Vector3d> hullA_, hullB_;
  std::vector<std::unique_ptr<Node>> arena_;
  std::priority_queue<OpenPair, std::vector<OpenPair>, std::greater<OpenPair>> open_;
};

}  // namespace

DistanceResult nurbsNurbs(const PosedModel& a, const PosedModel& b, const QueryContext& ctx) {
  const auto& ma = static_cast<const NurbsModel&>(a.model);
  const auto& mb = static_cast<const NurbsModel&>(b.model);
  const Eigen::Isometry3d X_AB = a.X_WM.inverse() * b.X_WM;
  PairSearch search(ma, mb, X_AB, ctx.tolerance);
  const bool finished = search.run();
  // Apart surfaces overlap only by containment: a point of either surface inside the other solid.
  const auto& cornerA = ma.forest().roots.front()->corners[0];
  const auto& cornerB = mb.forest().roots.front()->corners[0];
  const bool surfacesApart = finished && search.lower() > 0;
  const bool contained = surfacesApart && (mb.inside(X_AB.inverse() * cornerA) || ma.inside(X_AB * cornerB));
  if (contained && ctx.overlapVerdictOnly) return overlapVerdict();
  if (!surfacesApart || contained) return genericPair(a, b, ctx);
  search.polish();

  DistanceResult r;
  r.method = "nurbs-nurbs-tree-gjk";
  r.iterations = search.iterations();
  r.pointA = a.toWorld(search.pointA());
  r.pointB = a.toWorld(search.pointB());
  const Eigen::Vector3d gap = r.pointB - r.pointA;
  r.distance = gap.norm();
  r.normal = gap / r.distance;  // > 0: proved apart
  r.upperBound = r.distance;
  r.lowerBound = std::min(search.lower(), r.distance);
  settleStatus(r, ctx.tolerance);
  return r;
}

}  // namespace unidist::detail
