#include "pairs/nurbs_nurbs.h"

#include "convex/gjk.h"
#include "generic/generic_distance.h"
#include "nurbs/pair_newton.h"
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
// Pairs popped before the search stops with the bounds it has (a continuum of minima — a sphere centred on a
// torus's axis — can need far more at a tight tolerance). Small enough that such a case stays in milliseconds.
constexpr int kPairBudget = 20000;
constexpr double kFlatAngle = 0.5;  // a node with a narrower normal cone is polished by Newton when popped

using Node = nurbs::PatchNode;

struct OpenPair {
  double lower;
  const Node* a;
  const Node* b;
  Eigen::Vector3d wA, wB;  // GJK's closest hull points (A's frame)
  bool operator>(const OpenPair& o) const { return lower > o.lower; }
};

/// Where a search ended.
enum class Outcome { Proved, Touching, Exhausted };

// Thomas et al.'s bound-and-subdivide for the distance of two surfaces: best-first over pairs of patch-tree
// nodes. A pair is dropped when (a) its proved lower bound — balls, then GJK between the two subpatches'
// control-point hulls — cannot beat the best realised distance, or (b) it cannot hold an extremal pair: the
// directions from A's ball to B's ball must be parallel to both normal cones (or, on a patch edge, orthogonal
// to the edge's tangent cone; nodes holding a patch corner always qualify). Flat pairs are polished by Newton
// on the extremal-distance equations, which realises the minimum early; the search then only proves it.
class PairSearch {
 public:
  /// With stopWhenApart the search ends as soon as its lower bound is positive (an overlap verdict needs no more).
  PairSearch(const NurbsModel& a, const NurbsModel& b, const Eigen::Isometry3d& X_AB, double tolerance,
             bool stopWhenApart)
      : a_(a), b_(b), X_AB_(X_AB), R_BA_(X_AB.linear().transpose()), tolerance_(tolerance),
        stopWhenApart_(stopWhenApart) {}

  Outcome run() {
    seed();
    for (const auto& ra : a_.forest().roots)
      for (const auto& rb : b_.forest().roots) visit(ra.get(), rb.get());
    int popped = 0;
    while (!open_.empty()) {
      const OpenPair top = open_.top();
      // Surfaces within the tolerance may cross: proving them apart is not this search's job.
      if (best_.value <= 0.5 * tolerance_) return Outcome::Touching;
      if (top.lower >= best_.value - 0.5 * tolerance_ || (stopWhenApart_ && lower() > 0)) return Outcome::Proved;
      if (popped >= kPairBudget) return Outcome::Exhausted;
      open_.pop();
      ++popped;
      ++iterations_;
      if (isFlat(*top.a) && isFlat(*top.b) && awayFromBest(top)) polishFrom(*top.a, *top.b);
      const bool splitA = top.a->ball.radius >= top.b->ball.radius;
      const Node* n = splitA ? top.a : top.b;
      if (n->depth >= kMaxDepth) {
        lowerOfClosed_ = std::min(lowerOfClosed_, top.lower);
        continue;
      }
      for (const Node* c : (splitA ? a_.forest() : b_.forest()).children(*n, arena_))
        splitA ? visit(c, top.b) : visit(top.a, c);
    }
    return best_.value <= 0.5 * tolerance_ ? Outcome::Touching : Outcome::Proved;
  }

  double best() const { return best_.value; }
  double lower() const {
    const double open = open_.empty() ? std::numeric_limits<double>::infinity() : open_.top().lower;
    return std::min({open, lowerOfClosed_, lowerOfPruned_, best_.value});
  }
  const Eigen::Vector3d& pointA() const { return best_.pA; }
  const Eigen::Vector3d& pointB() const { return best_.pB; }
  int iterations() const { return iterations_; }

 private:
  struct Best : nurbs::PairHit {
    int patchA = -1, patchB = -1;
  };

  static bool isFlat(const Node& n) { return !n.normal.all && n.normal.angle <= kFlatAngle; }

  /// Newton from a pair next to the best one only finds the best one again: it runs where the pair's nearest
  /// hull points are a few node sizes from the best points (another basin), which, as the nodes shrink, every
  /// pair holding a nearer extremal pair eventually is.
  bool awayFromBest(const OpenPair& p) const {
    const double reach = 2 * (p.a->ball.radius + p.b->ball.radius);
    return !holdsBest(*p.a, *p.b) && ((p.wA - best_.pA).norm() > reach || (p.wB - best_.pB).norm() > reach);
  }

  /// The best pair's parameters lie in both nodes: Newton from them already ran.
  bool holdsBest(const Node& na, const Node& nb) const {
    const Eigen::Vector4d& x = best_.x;
    return best_.patchA == na.patch && best_.patchB == nb.patch && x[0] >= na.s0 && x[0] <= na.s1 &&
           x[1] >= na.t0 && x[1] <= na.t1 && x[2] >= nb.s0 && x[2] <= nb.s1 && x[3] >= nb.t0 && x[3] <= nb.t1;
  }

  void polish(int patchA, int patchB, const Eigen::Vector4d& x0) {
    const nurbs::PairHit h = nurbs::polishPair(a_.patches()[static_cast<std::size_t>(patchA)],
                                               b_.patches()[static_cast<std::size_t>(patchB)], X_AB_, x0);
    iterations_ += h.evaluations;
    if (h.value < best_.value) {
      static_cast<nurbs::PairHit&>(best_) = h;
      best_.patchA = patchA;
      best_.patchB = patchB;
    }
  }

  void polishFrom(const Node& na, const Node& nb) {
    polish(na.patch, nb.patch,
           Eigen::Vector4d(0.5 * (na.s0 + na.s1), 0.5 * (na.t0 + na.t1), 0.5 * (nb.s0 + nb.s1), 0.5 * (nb.t0 + nb.t1)));
  }

  /// The nearest pair of patch corners, then Newton from it: a realised upper bound before the search starts.
  void seed() {
    static const double kCornerS[4] = {0, 1, 0, 1}, kCornerT[4] = {0, 0, 1, 1};
    double nearest = std::numeric_limits<double>::infinity();
    Eigen::Vector4d x0 = Eigen::Vector4d::Zero();
    int pa = -1, pb = -1;
    for (const auto& ra : a_.forest().roots)
      for (const auto& rb : b_.forest().roots)
        for (std::size_t i = 0; i < 4; ++i)
          for (std::size_t j = 0; j < 4; ++j)
            if (const double d = (X_AB_ * rb->corners[j] - ra->corners[i]).squaredNorm(); d < nearest) {
              nearest = d;
              x0 = Eigen::Vector4d(kCornerS[i], kCornerT[i], kCornerS[j], kCornerT[j]);
              pa = ra->patch;
              pb = rb->patch;
            }
    if (pa >= 0) polish(pa, pb, x0);
  }

  static nurbs::Cone rotated(nurbs::Cone c, const Eigen::Matrix3d& R) {
    c.axis = R * c.axis;
    return c;
  }

  void visit(const Node* na, const Node* nb) {
    const Eigen::Vector3d cb = X_AB_ * nb->ball.center;
    // Rounding of the subdivided nets: the same 256 ulps the nodes' balls are widened by.
    const double eps = 256 * std::numeric_limits<double>::epsilon();
    const double margin = eps * (na->ball.center.norm() + na->ball.radius + cb.norm() + nb->ball.radius);
    // Balls first: a pair they already prune needs no GJK.
    const double byBalls = (cb - na->ball.center).norm() - na->ball.radius - nb->ball.radius - margin;
    if (byBalls >= best_.value - 0.5 * tolerance_) {
      lowerOfPruned_ = std::min(lowerOfPruned_, byBalls);
      return;
    }
    // Every segment from A's ball to B's ball points into `towards`; an extremal pair needs one of them
    // normal to both surfaces (or orthogonal to the edges they lie on).
    const nurbs::Cone towards = nurbs::coneTowards(cb, na->ball.center, na->ball.radius + nb->ball.radius);
    if (!nurbs::mayHoldCritical(*na, towards, true) || !nurbs::mayHoldCritical(*nb, rotated(towards, R_BA_), true))
      return;
    nurbs::controlPoints(*na, hullA_);
    nurbs::controlPoints(*nb, X_AB_, hullB_);
    // Overlapping hulls prove nothing about surfaces (at distance >= 0): their depth (EPA) is not worth
    // measuring; the separating-axis bound GJK leaves (negative) still orders the deeper overlaps first.
    const ConvexDistance c =
        convexDistance(supportOfPointSet(hullA_), supportOfPointSet(hullB_), 0.25 * tolerance_, kHullGjkCap, false);
    iterations_ += c.iterations;
    const double lower = std::min(c.lowerBound, c.distance) - margin;
    if (lower >= best_.value - 0.5 * tolerance_) {
      lowerOfPruned_ = std::min(lowerOfPruned_, lower);
      return;
    }
    open_.push({lower, na, nb, c.pointA, c.pointB});
  }

  const NurbsModel& a_;
  const NurbsModel& b_;
  Eigen::Isometry3d X_AB_;
  Eigen::Matrix3d R_BA_;
  double tolerance_;
  bool stopWhenApart_;
  Best best_ = [] {
    Best b;
    b.value = std::numeric_limits<double>::infinity();
    return b;
  }();
  double lowerOfClosed_ = std::numeric_limits<double>::infinity();  // pairs at the depth cap
  double lowerOfPruned_ = std::numeric_limits<double>::infinity();  // pairs dropped by their bound
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
  // A point of either model inside the other proves the overlap (apart surfaces overlap only so): the surface
  // search is spared (see insideSolid).
  const auto& cornerA = ma.forest().roots.front()->corners[0];
  const auto& cornerB = mb.forest().roots.front()->corners[0];
  if (insideSolid(mb, X_AB.inverse() * cornerA) || insideSolid(ma, X_AB * cornerB))
    return ctx.overlapVerdictOnly ? overlapVerdict() : genericPair(a, b, ctx);
  PairSearch search(ma, mb, X_AB, ctx.tolerance, ctx.overlapVerdictOnly);
  const Outcome outcome = search.run();
  // An exhausted search whose lower bound is still positive has proved the surfaces apart too.
  const bool surfacesApart = outcome != Outcome::Touching && search.lower() > 0;
  if (ctx.overlapVerdictOnly && outcome == Outcome::Touching) return notProvedApart(search.best());
  if (!surfacesApart) return genericPair(a, b, ctx);

  DistanceResult r;
  r.method = "nurbs-nurbs-cones-newton";
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
