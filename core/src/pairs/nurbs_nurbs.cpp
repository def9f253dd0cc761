#include "pairs/nurbs_nurbs.h"

#include "cloud/point_support.h"
#include "generic/generic_distance.h"
#include "generic/pair_polish.h"
#include "generic/translation_depth.h"
#include "nurbs/hull_distance.h"
#include "nurbs/pair_convexity.h"
#include "nurbs/pair_newton.h"
#include "nurbs/patch_tree.h"
#include "nurbs/support_ball.h"
#include "nurbs/support_bound.h"
#include "nurbs/support_tube.h"
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

constexpr int kHullGjkCap = 200;  // GJK on two small hulls converges in a few iterations; a guard only
constexpr int kMaxDepth = 40;     // beyond this, rounding and not the bound limits the nodes
// Pairs popped before the search stops with the bounds it has (a continuum of minima — a sphere centred on a
// torus's axis — can need far more at a tight tolerance). Small enough that such a case stays in milliseconds.
constexpr int kPairBudget = 20000;
// The penetration search's separation tests: one that needs more is as good as failed (surfaces crossing by less
// than the gap Newton realises there run any budget out: 3 s at the full one), and a failed test only widens the
// bisection's bracket by a step.
constexpr int kApartProofBudget = kPairBudget / 8;
constexpr double kFlatAngle = 0.5;  // a node with a narrower normal cone is polished by Newton when popped
constexpr double kRefitShare = 1e-3;  // of the tolerance: a best pair lowered by less keeps its separators
constexpr int kSeedPairs = 3;       // root pairs Newton starts from before the search
constexpr double kSameEnd = 1e-9;   // Newton ends this close in parameters are one (certified once)
constexpr double kFirstRegion = 1.0 / 32;  // the first convexity box tried around a Newton end (patch parameters)
constexpr int kRegionAttempts = 5;
constexpr double kSplitBothRatio = 0.5;  // the smaller node's ball at least this fraction of the larger's
constexpr double kRefusedSplitRatio = 4;  // the same, where the tube refused one side only (splitBothRatio)
constexpr double kNearBestShare = 0.7;    // a pair bounded above this share of the best is in the best's basin
constexpr int kRefusedAloneDepth = 3;     // refused nodes this deep are split with the other again
constexpr double kEscapeAlongNormal = 0.1;  // an escape direction must leave A's touching point at least this steeply
// Of the tolerance: a polish step across a seam shrinking the gap by less ends it. The answer is certified
// before the polish; at a coarse tolerance the search stops at its first Newton end, often on a seam of linked
// rings, and the alternating projections creep along their nearly constant gap (1e-1: 64 steps, 420 µs; now
// ~100 µs, 5e-6 off, against 180 µs at 1e-2).
constexpr double kSeamPolishShare = 1e-4;
constexpr double kFinerProof = 1e-14;  // a touching gap above this fraction of the size is proved by a finer search

using Node = nurbs::PatchNode;

struct OpenPair {
  double lower;
  const Node* a;
  const Node* b;
  Eigen::Vector3d wA, wB;  // GJK's closest hull points (A's frame)
  bool operator>(const OpenPair& o) const { return lower > o.lower; }
};

/// Where a search ended. Crossing: a Newton end's point lies inside the other solid (the solids overlap).
enum class Outcome { Proved, Touching, Crossing, Exhausted };

// Thomas et al.'s bound-and-subdivide for the distance of two surfaces: best-first over pairs of patch-tree
// nodes. A pair is dropped when (a) its proved lower bound — balls, then GJK between the two subpatches'
// control-point hulls — cannot beat the best realised distance, or (b) it cannot hold an extremal pair: the
// directions from A's ball to B's ball must be parallel to both normal cones (or, on a patch edge, orthogonal
// to the edge's tangent cone; nodes holding a patch corner always qualify). Newton on the extremal-distance
// equations (from the nearest patch corners, then the lowest root pairs until one run ends inside both patches,
// then from flat pairs away from earlier ends) realises the minimum early; the separators fitted at the best
// pair (support plane, ball, tube) settle pairs by one bound each; around each Newton end a convexity
// certificate (pair_convexity.h) proves a parameter box whose every pair is settled by the distance there, so
// the search stops a few levels below it instead of at node sizes of ~√tolerance, where the hull bounds would
// meet the tolerance.
class PairSearch {
 public:
  /// With stopWhenApart the search ends as soon as its lower bound is positive (an overlap verdict needs no more).
  PairSearch(const NurbsModel& a, const NurbsModel& b, const Eigen::Isometry3d& X_AB, double tolerance,
             bool stopWhenApart, int budget = kPairBudget)
      : a_(a), b_(b), X_AB_(X_AB), R_BA_(X_AB.linear().transpose()), tolerance_(tolerance),
        stopWhenApart_(stopWhenApart), budget_(budget) {}

  Outcome run() {
    const bool interiorEnd = seed();
    updateSeparators();
    for (const auto& ra : a_.forest().roots)
      for (const auto& rb : b_.forest().roots) visit(ra.get(), rb.get());
    seedFromLowestPairs(interiorEnd);
    int popped = 0;
    while (!open_.empty()) {
      if (inside_) return Outcome::Crossing;
      const OpenPair top = open_.top();
      // Surfaces within the tolerance may cross: proving them apart is not this search's job.
      if (best_.value <= 0.5 * tolerance_) return Outcome::Touching;
      if (top.lower >= best_.value - 0.5 * tolerance_ || (stopWhenApart_ && lower() > 0)) return Outcome::Proved;
      if (popped >= budget_) return Outcome::Exhausted;
      open_.pop();
      ++popped;
      if (settledByRegion(*top.a, *top.b)) continue;
      updateSeparators();
      if (settledBySeparator(*top.a, *top.b, roundingMargin(*top.a, X_AB_ * top.b->ball.center, *top.b))) continue;
      certifyAround(*top.a, *top.b);
      if (settledByRegion(*top.a, *top.b)) continue;
      ++iterations_;
      if (isFlat(*top.a) && isFlat(*top.b) && !nearNewtonEnd(top)) polishFrom(*top.a, *top.b);
      // The larger node, unless the tube proved it on its side and not the other (splitting it settles nothing).
      const int unproved = tube_ ? tube_->lastUnproved() : 0;
      const bool splitA = unproved != 0 ? unproved < 0 : top.a->ball.radius >= top.b->ball.radius;
      const Node* n = splitA ? top.a : top.b;
      if (n->depth >= kMaxDepth) {
        lowerOfClosed_ = std::min(lowerOfClosed_, top.lower);
        continue;
      }
      // Nodes of about the same size are both split at once: their children's pairs are visited without the
      // intermediate pairs (one node split) being pushed and popped. Only while the children are kept in the
      // trees: building nodes below kCachedDepth costs more than the pops it saves.
      const Node* other = splitA ? top.b : top.a;
      if (other->ball.radius >= splitBothRatio(top, unproved) * n->ball.radius &&
          top.a->depth < nurbs::kCachedDepth && top.b->depth < nurbs::kCachedDepth) {
        const auto childrenA = a_.forest().children(*top.a, arena_);
        const auto childrenB = b_.forest().children(*top.b, arena_);
        for (const Node* ca : childrenA)
          for (const Node* cb : childrenB) visit(ca, cb, top.wB - top.wA, top.a, top.b);
        ++popped;  // counted twice: a search the budget stops does about the work it did with one-node splits
        continue;
      }
      for (const Node* c : (splitA ? a_.forest() : b_.forest()).children(*n, arena_))
        splitA ? visit(c, top.b, top.wB - top.wA, top.a, top.b) : visit(top.a, c, top.wB - top.wA, top.a, top.b);
    }
    if (inside_) return Outcome::Crossing;
    return best_.value <= 0.5 * tolerance_ ? Outcome::Touching : Outcome::Proved;
  }

  /// How much larger than the node split the other must be to be split with it. Where the tube refused one
  /// side only, at a pair bounded near the best (the best pair's own basin), the other's pieces are proved as it
  /// is: splitting it would only multiply the pairs and the Newton runs from flat ones (linked rings: −25 %
  /// instructions), so it is split only when much larger. Not far below the best (a lower minimum may lie there:
  /// both are split, for the flat pairs Newton starts from), and only near the roots: where the tube cannot
  /// prove the refused side at all (at a tolerance of 1e-12 the convexity boxes settle the contact), holding the
  /// other large left the search splitting one side only, past its budget.
  double splitBothRatio(const OpenPair& top, int unproved) const {
    if (unproved == 0 || (unproved < 0 ? top.a : top.b)->depth >= kRefusedAloneDepth) return kSplitBothRatio;
    return top.lower >= kNearBestShare * best_.value ? kRefusedSplitRatio : kSplitBothRatio;
  }

  double best() const { return best_.value; }
  /// After Outcome::Crossing: the point (A's frame) proved inside the other solid.
  const std::optional<Eigen::Vector3d>& pointInside() const { return inside_; }
  double lower() const {
    const double open = open_.empty() ? std::numeric_limits<double>::infinity() : open_.top().lower;
    return std::min({open, lowerOfClosed_, lowerOfPruned_, best_.value});
  }
  const Eigen::Vector3d& pointA() const { return best_.pA; }
  const Eigen::Vector3d& pointB() const { return best_.pB; }
  /// Does the best pair lie on a patch edge of either model (a Newton run clamped there)?
  bool bestOnPatchEdge() const { return !isInterior(best_.x); }
  /// A's outward unit normal at the best pair's point on A (A's frame).
  Eigen::Vector3d normalA() const { return a_.patchNormal(best_.patchA, best_.x[0], best_.x[1]); }
  int iterations() const { return iterations_; }

 private:
  struct Best : nurbs::PairHit {
    int patchA = -1, patchB = -1;
  };
  /// Where Newton ended (a stationary point, or a box corner): a centre for a convexity certificate.
  struct NewtonEnd {
    int patchA, patchB;
    Eigen::Vector4d x;
    Eigen::Vector3d pA, pB;
    bool tried = false;
  };
  /// A box of two patches' parameters: A's s, t, then B's u, v.
  struct ParamBox {
    Eigen::Vector4d lo, hi;
    bool contains(const Eigen::Vector4d& x) const {
      return (x.array() >= lo.array()).all() && (x.array() <= hi.array()).all();
    }
    bool within(const ParamBox& o) const { return (lo.array() >= o.lo.array()).all() && (hi.array() <= o.hi.array()).all(); }
  };
  static ParamBox boxOf(const Node& na, const Node& nb) {
    return {Eigen::Vector4d(na.s0, na.t0, nb.s0, nb.t0), Eigen::Vector4d(na.s1, na.t1, nb.s1, nb.t1)};
  }
  /// A box over which the squared distance is proved convex: every pair of nodes inside it is bounded below by
  /// `lower` at once.
  struct ConvexRegion {
    int patchA, patchB;
    ParamBox box;
    double lower;
  };

  /// A pair inside a certified region whose bound cannot beat the best is settled by that bound.
  bool settledByRegion(const Node& na, const Node& nb) {
    for (const ConvexRegion& r : regions_)
      if (r.patchA == na.patch && r.patchB == nb.patch && r.lower >= best_.value - 0.5 * tolerance_ &&
          boxOf(na, nb).within(r.box)) {
        lowerOfPruned_ = std::min(lowerOfPruned_, r.lower);
        return true;
      }
    return false;
  }

  /// Certifies convexity around every untried Newton end inside the pair: boxes centred on it, from 1/32 of the
  /// patch down, each next size from how far the last one missed (the certificate's ratio grows with the box).
  /// Not before the pair is as small as that first box: a region settles only pairs inside it, and around an end
  /// above the best the search often stops (the hull bounds rising past the best) before pairs get that small.
  void certifyAround(const Node& na, const Node& nb) {
    const ParamBox pair = boxOf(na, nb);
    if ((pair.hi - pair.lo).maxCoeff() > kFirstRegion) return;
    for (NewtonEnd& e : ends_) {
      if (e.tried || e.patchA != na.patch || e.patchB != nb.patch) continue;
      const Eigen::Vector4d& x = e.x;
      if (!boxOf(na, nb).contains(x)) continue;
      e.tried = true;
      double size = kFirstRegion;
      for (int attempt = 0; attempt < kRegionAttempts; ++attempt) {
        const Eigen::Vector4d lo = (x.array() - 0.5 * size).max(0.0), hi = (x.array() + 0.5 * size).min(1.0);
        const nurbs::ConvexityCertificate c =
            nurbs::certifyConvexPair(a_.patches()[static_cast<std::size_t>(e.patchA)],
                                     b_.patches()[static_cast<std::size_t>(e.patchB)], X_AB_, lo, hi, x);
        if (c.proved) {
          regions_.push_back({e.patchA, e.patchB, {lo, hi}, c.lower});
          break;
        }
        if (!std::isfinite(c.ratio)) break;  // not a strict minimum there: no box around it is convex
        size *= std::min(0.9, std::sqrt(0.6 / c.ratio));
      }
    }
  }

  /// The plane through the best pair's points, normal to their segment: every pair of nodes is at least
  /// (B's least height above it) − (A's greatest height) apart. Heights from the control points, or where their
  /// bulge decides, certified exactly (support_bound.h): near a locally convex contact the nodes holding the
  /// closest points are settled by it, at any size.
  struct SupportPlane {
    double forBest = std::numeric_limits<double>::quiet_NaN();  // the best value it was made for
    Eigen::Vector3d n = Eigen::Vector3d::Zero(), nB = Eigen::Vector3d::Zero();  // A's frame; nB = R_BA n
    double atA = 0, atB = 0;  // n·pA, n·pB
    // Both surfaces curve away from the plane at the best pair. Only then is it used: elsewhere (a saddle on
    // either side) it settles few pairs that the parent's direction does not, and costs a scan per visit.
    bool convexContact = false;
    nurbs::NodeMemo certifiedA, certifiedB;  // A's greatest, B's least height (±inf: not proved)
  };

  /// The separators for the best pair, remade when it changes: the plane, used at a convex contact, else the
  /// ball where one fits.
  void updateSeparators() {
    if (plane_.forBest == best_.value || !std::isfinite(best_.value)) return;
    // The same minimum reached again, lower by rounding: the separators are kept. Any plane, ball or tube bounds
    // the pairs soundly (only their fit makes them sharp), and a new fit would throw their certificates away.
    if (plane_.forBest - best_.value <= kRefitShare * tolerance_) return;
    plane_ = {};
    ball_.reset();
    std::optional<nurbs::SupportTube> kept = std::move(tube_);
    tube_.reset();
    plane_.forBest = best_.value;
    const Eigen::Vector3d gap = best_.pB - best_.pA;
    if (!(gap.norm() > 0)) return;
    plane_.n = gap.normalized();
    plane_.nB = R_BA_ * plane_.n;
    plane_.atA = plane_.n.dot(best_.pA);
    plane_.atB = plane_.n.dot(best_.pB);
    plane_.convexContact =
        curvesAway(a_.patches()[static_cast<std::size_t>(best_.patchA)], best_.x.head<2>(), plane_.n) &&
        curvesAway(b_.patches()[static_cast<std::size_t>(best_.patchB)], best_.x.tail<2>(), -plane_.nB);
    if (plane_.convexContact) return;
    const nurbs::SeparatorContact contact{a_.patches()[static_cast<std::size_t>(best_.patchA)], best_.x.head<2>(),
                                          b_.patches()[static_cast<std::size_t>(best_.patchB)], best_.x.tail<2>(),
                                          X_AB_, best_.pA, best_.pB};
    ball_ = nurbs::SupportBall::fit(contact);
    if (ball_) return;
    tube_ = nurbs::SupportTube::fit(contact, best_.value - 0.5 * tolerance_, tolerance_);
    // The same tube (a ring's core circle, fitted again at a lower pair on it) keeps the proofs it has made.
    if (kept && tube_ && kept->narrowTo(*tube_, kRefitShare * tolerance_)) tube_ = std::move(kept);
  }

  /// Does the surface at (s, t) curve away from the plane through it normal to n (on n's side), to first
  /// approximation: the height n·S has a negative semidefinite Hessian there (a flat direction allowed)?
  static bool curvesAway(const RationalBezierPatch& patch, const Eigen::Vector2d& st, const Eigen::Vector3d& n) {
    const SurfaceDerivatives d = patch.derivatives(st[0], st[1]);
    const double uu = n.dot(d.duu), uv = n.dot(d.duv), vv = n.dot(d.dvv);
    const double flat = 1e-9 * (d.duu.norm() + d.duv.norm() + d.dvv.norm());
    return uu <= flat && vv <= flat && (flat - uu) * (flat - vv) >= uv * uv;
  }

  static double certifiedHeight(nurbs::NodeMemo& memo, const Node& node, const Eigen::Vector3d& direction) {
    // Normals every way: no direction sees the node curving away from it (and the cone test cannot say).
    if (node.normal.all) return std::numeric_limits<double>::infinity();
    return memo.get(node, [&] {
      const nurbs::SupportBound b = nurbs::certifySupport(node.net, direction);
      return b.proved ? b.upper : std::numeric_limits<double>::infinity();
    });
  }

  /// The plane's lower bound for the pair (without the rounding margin).
  double planeGap(const Node& na, const Node& nb) {
    const Eigen::Vector3d& n = plane_.n;
    const HullHeights hull = hullHeights(na, nb, n, plane_.nB);
    double maxA = hull.greatestA, minB = hull.leastB;
    const double needed = best_.value - 0.5 * tolerance_;
    if (minB - maxA >= needed) return minB - maxA;
    // A certified height is no better than the highest surface point known, a corner: certify only when the
    // corners leave room (around a saddle they cross the plane).
    const bool tryA = maxA > plane_.atA, tryB = minB < plane_.atB;
    double cornerA = -std::numeric_limits<double>::infinity(), cornerB = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 4; ++k) {
      cornerA = std::max(cornerA, n.dot(na.corners[static_cast<std::size_t>(k)]));
      cornerB = std::min(cornerB, plane_.nB.dot(nb.corners[static_cast<std::size_t>(k)]));
    }
    const double shiftB = n.dot(X_AB_.translation());  // B's heights are taken in B's frame
    if ((tryB ? shiftB + cornerB : minB) - (tryA ? cornerA : maxA) < needed) return minB - maxA;
    if (tryA) maxA = std::min(maxA, certifiedHeight(plane_.certifiedA, na, n));
    if (tryB) minB = std::max(minB, shiftB - certifiedHeight(plane_.certifiedB, nb, -plane_.nB));
    return minB - maxA;
  }

  /// Settled by the best pair's separator (margin: the rounding allowance of visit()): the plane at a convex
  /// contact, else the ball (support_ball.h) where one fits.
  /// parentA, parentB: the nodes holding na and nb (see SupportBall::gap), null at the roots.
  bool settledBySeparator(const Node& na, const Node& nb, double margin, const Node* parentA = nullptr,
                          const Node* parentB = nullptr) {
    const double needed = best_.value - 0.5 * tolerance_;
    double lower;
    if (plane_.convexContact) lower = planeGap(na, nb) - margin;
    else if (ball_) lower = ball_->gap(na, nb, needed + margin, parentA, parentB) - margin;
    else if (tube_) lower = tube_->gap(na, nb) - margin;
    else return false;
    if (lower < needed) return false;
    lowerOfPruned_ = std::min(lowerOfPruned_, lower);
    return true;
  }

  static bool isFlat(const Node& n) { return !n.normal.all && n.normal.angle <= kFlatAngle; }

  /// Newton from a pair next to where Newton already ended in the same two patches only finds that end again:
  /// it runs where the pair's nearest hull points are a few node sizes from every such end (another basin), or
  /// in two patches where it never ran (the same minimum across a patch seam: its end there lets the seam's
  /// side be certified too).
  bool nearNewtonEnd(const OpenPair& p) const {
    const Node& na = *p.a;
    const Node& nb = *p.b;
    const double reach = 2 * (na.ball.radius + nb.ball.radius);
    for (const NewtonEnd& e : ends_)
      if (e.patchA == na.patch && e.patchB == nb.patch &&
          ((e.pA - p.wA).norm() <= reach && (e.pB - p.wB).norm() <= reach))
        return true;
    return false;
  }

  /// The parameters of the node's control point nearest p (its Greville point, roughly where p lies).
  static Eigen::Vector2d nearestControlParameters(const Node& n, const Eigen::Vector3d& p) {
    const int du = n.net.degreeU, dv = n.net.degreeV;
    double nearest = std::numeric_limits<double>::infinity();
    Eigen::Vector2d st(0.5 * (n.s0 + n.s1), 0.5 * (n.t0 + n.t1));
    for (int i = 0; i <= du; ++i)
      for (int j = 0; j <= dv; ++j)
        if (const double d = (n.points[static_cast<std::size_t>(i * (dv + 1) + j)] - p).squaredNorm(); d < nearest) {
          nearest = d;
          st = {n.s0 + (n.s1 - n.s0) * i / std::max(du, 1), n.t0 + (n.t1 - n.t0) * j / std::max(dv, 1)};
        }
    return st;
  }

  /// A near-optimal upper bound before the search descends: Newton from the root pairs with the lowest bounds,
  /// started where their control hulls come closest.
  /// interiorEnd: Newton already ended inside two patches (no root-pair seeds then).
  void seedFromLowestPairs(bool interiorEnd) {
    std::vector<OpenPair> lowest;
    for (int k = 0; k < kSeedPairs && !open_.empty(); ++k) {
      lowest.push_back(open_.top());
      open_.pop();
    }
    for (const OpenPair& p : lowest) {
      open_.push(p);
      // An end inside both patches is a stationary pair, most likely the minimum's: the other seeds would end
      // on its patches' edges (the search still starts Newton wherever it finds a flat pair away from it).
      if (interiorEnd) continue;
      const Eigen::Vector2d sa = nearestControlParameters(*p.a, p.wA);
      const Eigen::Vector2d sb = nearestControlParameters(*p.b, R_BA_ * (p.wB - X_AB_.translation()));
      const Eigen::Vector4d end = polish(p.a->patch, p.b->patch, Eigen::Vector4d(sa[0], sa[1], sb[0], sb[1]));
      interiorEnd = isInterior(end);
    }
  }

  /// Newton from x0 in the two patches; returns where it ended.
  Eigen::Vector4d polish(int patchA, int patchB, const Eigen::Vector4d& x0) {
    const nurbs::PairHit h = nurbs::polishPair(a_.patches()[static_cast<std::size_t>(patchA)],
                                               b_.patches()[static_cast<std::size_t>(patchB)], X_AB_, x0);
    iterations_ += h.evaluations;
    if (std::none_of(ends_.begin(), ends_.end(), [&](const NewtonEnd& e) {
          return e.patchA == patchA && e.patchB == patchB && (e.x - h.x).cwiseAbs().maxCoeff() <= kSameEnd;
        }))
      ends_.push_back({patchA, patchB, h.x, h.pA, h.pB});
    if (h.value < best_.value) {
      static_cast<nurbs::PairHit&>(best_) = h;
      best_.patchA = patchA;
      best_.patchB = patchB;
      noteCrossing(patchA);
    }
    return h.x;
  }

  /// Solids crossing by a sliver (stacked rings sunk 1e-8 into each other along a circle) leave Newton stationary
  /// pairs short of zero, and every pair along the sliver unsettled: the search would run its whole budget.
  /// A best pair whose B point lies behind A's tangent plane there is tested: a point proved inside the other
  /// solid ends the search as crossing.
  void noteCrossing(int patchA) {
    if (inside_ || !a_.isSolid() || !b_.isSolid() || !(best_.value > 0.5 * tolerance_)) return;
    const Eigen::Vector3d outward = a_.patchNormal(patchA, best_.x[0], best_.x[1]);
    if (!(outward.dot(best_.pB - best_.pA) < 0)) return;
    if (insideSolid(a_, best_.pB)) inside_ = best_.pB;
    else if (insideSolid(b_, X_AB_.inverse() * best_.pA)) inside_ = best_.pA;
  }

  void polishFrom(const Node& na, const Node& nb) {
    polish(na.patch, nb.patch,
           Eigen::Vector4d(0.5 * (na.s0 + na.s1), 0.5 * (na.t0 + na.t1), 0.5 * (nb.s0 + nb.s1), 0.5 * (nb.t0 + nb.t1)));
  }

  /// The nearest pair of patch corners, then Newton from it: a realised upper bound before the search starts.
  /// Over the distinct corners (a torus's 64 are 16 points); of equally near pairs, the first in (patch of A,
  /// patch of B, corner of A, corner of B) order.
  /// Newton from the nearest pair of patch corners; returns whether it ended inside both patches.
  bool seed() {
    static const double kCornerS[4] = {0, 1, 0, 1}, kCornerT[4] = {0, 0, 1, 1};
    const auto& cornersA = a_.forest().distinctCorners;
    const auto& cornersOfB = b_.forest().distinctCorners;
    std::vector<Eigen::Vector3d> cornersB;  // in A's frame, mapped once
    cornersB.reserve(cornersOfB.size());
    for (const auto& c : cornersOfB) cornersB.push_back(X_AB_ * c.point);
    double nearest = std::numeric_limits<double>::infinity();
    std::array<int, 4> first{};  // (patch A, patch B, corner A, corner B) of the nearest pair
    for (const auto& ca : cornersA)
      for (std::size_t kb = 0; kb < cornersB.size(); ++kb) {
        const double d = (cornersB[kb] - ca.point).squaredNorm();
        if (d > nearest) continue;
        const std::array<int, 4> key{ca.root, cornersOfB[kb].root, ca.corner, cornersOfB[kb].corner};
        if (d < nearest || key < first) {
          nearest = d;
          first = key;
        }
      }
    if (!(nearest < std::numeric_limits<double>::infinity())) return false;
    const int pa = a_.forest().roots[static_cast<std::size_t>(first[0])]->patch;
    const int pb = b_.forest().roots[static_cast<std::size_t>(first[1])]->patch;
    return isInterior(
        polish(pa, pb, Eigen::Vector4d(kCornerS[first[2]], kCornerT[first[2]], kCornerS[first[3]], kCornerT[first[3]])));
  }

  static bool isInterior(const Eigen::Vector4d& x) { return (x.array() > 0).all() && (x.array() < 1).all(); }

  static nurbs::Cone rotated(nurbs::Cone c, const Eigen::Matrix3d& R) {
    c.axis = R * c.axis;
    return c;
  }

  /// min over B's hull of n·b − max over A's hull of n·a: a lower bound of the hulls' distance for unit n (B's
  /// points in B's frame: n·(X p) = n·t + (Rᵀn)·p). Also the points attaining both: the hulls' supports along n
  /// and −n (A's frame), where GJK starts.
  double hullGap(const Node& na, const Node& nb, const Eigen::Vector3d& n, Eigen::Vector3d& supportA,
                 Eigen::Vector3d& supportB) const {
    const HullHeights h = hullHeights(na, nb, n, R_BA_ * n);
    supportA = *h.pointA;
    supportB = X_AB_ * *h.pointB;
    return h.leastB - h.greatestA;
  }

  /// Along unit n (A's frame; nB = R_BA n): the greatest height of A's control points and the least of B's
  /// (B's in A's frame: n·(X p) = n·t + nB·p), and the points attaining them (each in its own frame).
  struct HullHeights {
    double greatestA, leastB;
    const Eigen::Vector3d* pointA;
    const Eigen::Vector3d* pointB;
  };
  HullHeights hullHeights(const Node& na, const Node& nb, const Eigen::Vector3d& n, const Eigen::Vector3d& nB) const {
    const Eigen::Vector3d& pA = supportOfPoints(na.points, n);
    const Eigen::Vector3d& pB = supportOfPoints(nb.points, -nB);
    return {n.dot(pA), n.dot(X_AB_.translation()) + nB.dot(pB), &pA, &pB};
  }

  /// Rounding of the subdivided nets: the same 256 ulps the nodes' balls are widened by (cb: B's ball centre in
  /// A's frame).
  static double roundingMargin(const Node& na, const Eigen::Vector3d& cb, const Node& nb) {
    const double eps = 256 * std::numeric_limits<double>::epsilon();
    return eps * (na.ball.center.norm() + na.ball.radius + cb.norm() + nb.ball.radius);
  }

  /// hint: a direction from A toward B along which the pair is likely separated (the parent's), or zero.
  /// parentA, parentB: the popped pair's nodes holding na and nb, null at the roots.
  void visit(const Node* na, const Node* nb, const Eigen::Vector3d& hint = Eigen::Vector3d::Zero(),
             const Node* parentA = nullptr, const Node* parentB = nullptr) {
    const Eigen::Vector3d cb = X_AB_ * nb->ball.center;
    const double margin = roundingMargin(*na, cb, *nb);
    // Balls first: a pair they already prune needs no GJK.
    const double byBalls = (cb - na->ball.center).norm() - na->ball.radius - nb->ball.radius - margin;
    if (byBalls >= best_.value - 0.5 * tolerance_) {
      lowerOfPruned_ = std::min(lowerOfPruned_, byBalls);
      return;
    }
    if (settledByRegion(*na, *nb) || settledBySeparator(*na, *nb, margin, parentA, parentB)) return;
    // The hulls' gap along one direction is a proved bound too: along the parent pair's closest-point direction
    // (or between the balls' centres) it often prunes the pair without running GJK. (Along the best pair's
    // direction from the control points alone: more instructions than the GJK runs it saves; the support plane
    // above certifies that direction's heights, and only at a convex contact.)
    const Eigen::Vector3d start = hint.squaredNorm() > 0 ? hint : Eigen::Vector3d(cb - na->ball.center);
    Eigen::Vector3d startA = na->points.front(), startB = X_AB_ * nb->points.front();
    if (const double n = start.norm(); n > 0) {
      const double byAxis = hullGap(*na, *nb, start / n, startA, startB) - margin;
      if (byAxis >= best_.value - 0.5 * tolerance_) {
        lowerOfPruned_ = std::min(lowerOfPruned_, byAxis);
        return;
      }
    }
    // Every segment from A's ball to B's ball points into `towards`; an extremal pair needs one of them
    // normal to both surfaces (or orthogonal to the edges they lie on).
    // (Nodes whose normals point every way pass whatever the cone: it is not worth its arcsine then.)
    if (!na->normal.all || !nb->normal.all) {
      const nurbs::Cone towards = nurbs::coneTowards(cb, na->ball.center, na->ball.radius + nb->ball.radius);
      if (!nurbs::mayHoldCritical(*na, towards, true) || !nurbs::mayHoldCritical(*nb, rotated(towards, R_BA_), true))
        return;
    }
    // Overlapping hulls prove nothing about surfaces (at distance >= 0): their depth is not worth measuring; the
    // separating-axis bound GJK leaves (negative) still orders the deeper overlaps first. GJK stops as soon as
    // its bound prunes the pair.
    const double prune = best_.value - 0.5 * tolerance_ + margin;
    const nurbs::HullDistance c =
        nurbs::hullDistance(na->points, nb->points, X_AB_, startA, startB, 0.25 * tolerance_, kHullGjkCap, prune);
    iterations_ += c.iterations;
    const double lower = c.lower - margin;
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
  int budget_;
  Best best_ = [] {
    Best b;
    b.value = std::numeric_limits<double>::infinity();
    return b;
  }();
  double lowerOfClosed_ = std::numeric_limits<double>::infinity();  // pairs at the depth cap
  double lowerOfPruned_ = std::numeric_limits<double>::infinity();  // pairs dropped by their bound
  int iterations_ = 0;
  std::optional<Eigen::Vector3d> inside_;  // a best pair's point proved inside the other solid
  std::vector<NewtonEnd> ends_;
  std::vector<ConvexRegion> regions_;
  SupportPlane plane_;
  std::optional<nurbs::SupportBall> ball_;
  std::optional<nurbs::SupportTube> tube_;
  std::vector<std::unique_ptr<Node>> arena_;
  std::priority_queue<OpenPair, std::vector<OpenPair>, std::greater<OpenPair>> open_;
};

/// Solids whose surfaces meet or cross: both proved convex, GJK/EPA on their support maps (the depth is the
/// minimum of their Minkowski difference's support function); otherwise, from a point where the surfaces meet
/// (contact_W, when the search found one), the escape at the deepest point near it, which settles a shallow
/// overlap, and else the generic translation-depth search.
DistanceResult meeting(const PosedModel& a, const PosedModel& b, const QueryContext& ctx,
                       const std::optional<Eigen::Vector3d>& contact_W = std::nullopt) {
  if (!convexSolid(a.model) || !convexSolid(b.model)) {
    if (contact_W && !ctx.overlapVerdictOnly)  // (a verdict goes on to the generic routine's own)
      if (std::optional<DistanceResult> r = shallowDepth(a, b, ctx, *contact_W)) return *r;
    return genericPair(a, b, ctx);
  }
  DistanceResult r = convexPairOfSupports(supportMapOf(a), supportMapOf(b), ctx);
  r.method = "gjk-epa-proved-convex";
  return r;
}

/// The first patch corner of either model when it lies inside the other (B posed at X_AB; A's frame): with the
/// surfaces apart, the one way the solids can still overlap is containment, which this tells.
std::optional<Eigen::Vector3d> firstCornerInside(const NurbsModel& ma, const NurbsModel& mb,
                                                 const Eigen::Isometry3d& X_AB) {
  const Eigen::Vector3d& cornerA = ma.forest().roots.front()->corners[0];
  if (insideSolid(mb, X_AB.inverse() * cornerA)) return cornerA;
  const Eigen::Vector3d cornerB = X_AB * mb.forest().roots.front()->corners[0];
  if (insideSolid(ma, cornerB)) return cornerB;
  return std::nullopt;
}

/// Whether a distinct patch corner of either model lies inside the other (B posed at X_AB in A's frame).
bool cornerInside(const NurbsModel& ma, const NurbsModel& mb, const Eigen::Isometry3d& X_AB) {
  const Eigen::Isometry3d X_BA = X_AB.inverse();
  for (const nurbs::PatchForest::Corner& c : ma.forest().distinctCorners)
    if (insideSolid(mb, X_BA * c.point)) return true;
  for (const nurbs::PatchForest::Corner& c : mb.forest().distinctCorners)
    if (insideSolid(ma, X_AB * c.point)) return true;
  return false;
}

/// Surfaces within the tolerance of each other in a verdict-only query: the solids overlap when a point of one
/// lies inside the other. Tried: every distinct patch corner of each model, then a grid of points on every patch,
/// then the deepest points of a short search of each surface through the other's field (seedOverlap). False when
/// none is found inside (touching, or an overlap too thin to see): the caller then measures in full, which used to
/// be the only way (the whole translation-depth search: 0.5 s for crossing tori, where a point inside takes
/// microseconds).
bool overlapWitnessed(const PosedModel& a, const PosedModel& b, const QueryContext& ctx) {
  const auto& ma = static_cast<const NurbsModel&>(a.model);
  const auto& mb = static_cast<const NurbsModel&>(b.model);
  const Eigen::Isometry3d X_AB = a.X_WM.inverse() * b.X_WM, X_BA = X_AB.inverse();
  if (cornerInside(ma, mb, X_AB)) return true;
  constexpr int kGrid = 4;  // interior grid points per patch side
  for (int i = 1; i <= kGrid; ++i)
    for (int j = 1; j <= kGrid; ++j) {
      const double s = static_cast<double>(i) / (kGrid + 1), t = static_cast<double>(j) / (kGrid + 1);
      for (const RationalBezierPatch& p : ma.patches())
        if (insideSolid(mb, X_BA * p.evaluate(s, t))) return true;
      for (const RationalBezierPatch& p : mb.patches())
        if (insideSolid(ma, X_AB * p.evaluate(s, t))) return true;
    }
  return seedOverlap(a, b, ctx).provedDepth > ctx.tolerance;
}

/// Are the solids proved interior-disjoint with B posed at X_AB (A's frame)? No patch corner of either inside the
/// other (containment) and the surfaces proved apart by the search at `tolerance`.
bool provedApart(const NurbsModel& ma, const NurbsModel& mb, const Eigen::Isometry3d& X_AB, double tolerance) {
  if (firstCornerInside(ma, mb, X_AB)) return false;
  PairSearch search(ma, mb, X_AB, tolerance, true);
  const Outcome outcome = search.run();
  return outcome != Outcome::Touching && outcome != Outcome::Crossing && search.lower() > 0;
}

/// Surfaces touching (within half the tolerance: the search's realised gap), certified by the first of:
///  * the supporting planes across A's outward normal at the touching point, when their gap is within the
///    tolerance (two tori stacked touch along a circle in one plane);
///  * an escape: B moved by half the tolerance and then proved apart bounds the depth by that, so the signed
///    distance lies in [−tol/2, gap]. Directions: A's outward normal there, the line of the models' centres, A's
///    and B's axes both ways (a ball resting in a ring's hole touches along a circle and leaves along the ring's
///    axis, not along any one contact's normal);
///  * a finer search proving a realised gap above rounding.
/// Empty when none does (the solids may cross): the generic routine answers.
std::optional<DistanceResult> settleTouching(const PosedModel& a, const PosedModel& b, const QueryContext& ctx,
                                             const PairSearch& search) {
  const auto& ma = static_cast<const NurbsModel&>(a.model);
  const auto& mb = static_cast<const NurbsModel&>(b.model);
  const double gap = search.best();
  DistanceResult r;
  r.pointA = a.toWorld(search.pointA());
  r.pointB = a.toWorld(search.pointB());
  r.distance = r.upperBound = gap;
  const Eigen::Vector3d outward = a.dirToWorld(search.normalA());
  // The supporting planes across A's normal there first: two tori stacked touch along a circle in one plane.
  if (const double plane = supportGapLowerBound(a, b, outward); plane >= gap - ctx.tolerance) {
    r.method = "nurbs-nurbs-touching-plane";
    r.normal = gap > 0 ? Eigen::Vector3d((r.pointB - r.pointA) / gap) : outward;
    r.lowerBound = std::min(plane, gap);
    settleStatus(r, ctx.tolerance);
    return r;
  }
  std::vector<Eigen::Vector3d> directions = {outward, b.toWorld(mb.localBoundingSphere().center) -
                                                          a.toWorld(ma.localBoundingSphere().center)};
  for (const Eigen::Vector3d& axis : axesOfBoth(a, b)) directions.push_back(axis);
  const double step = 0.5 * ctx.tolerance;
  for (Eigen::Vector3d m : directions) {
    if (!(m.norm() > 0)) continue;
    m.normalize();
    if (!(m.dot(outward) > kEscapeAlongNormal)) continue;  // into A at the known contact
    const Eigen::Isometry3d X_WB = Eigen::Translation3d(step * m) * b.X_WM;
    if (!provedApart(ma, mb, a.X_WM.inverse() * X_WB, ctx.tolerance / 16)) continue;
    r.method = "nurbs-nurbs-touching-escape";
    // The contract ties the normal to the points (point_b − point_a = distance · normal); only where they coincide
    // is it free, and then the way B leaves is the one worth giving.
    r.normal = gap > 0 ? Eigen::Vector3d((r.pointB - r.pointA) / gap) : m;
    r.lowerBound = -step;
    settleStatus(r, ctx.tolerance);
    return r;
  }
  // No escape, but a realised gap above rounding: a search at a quarter of it proves the surfaces apart, and the
  // signed distance then lies in [0, gap] (a ball in a ring's hole 1e-9 from it at a tolerance of 1e-6, where no
  // short translation frees it: it touches all round).
  const Eigen::Isometry3d X_AB = a.X_WM.inverse() * b.X_WM;
  if (gap >= kFinerProof * ma.localBounds().diagonal() && provedApart(ma, mb, X_AB, 0.25 * gap)) {
    r.method = "nurbs-nurbs-cones-newton";
    r.normal = (r.pointB - r.pointA) / gap;
    r.lowerBound = 0;
    settleStatus(r, ctx.tolerance);
    return r;
  }
  return std::nullopt;
}

}  // namespace

DistanceResult nurbsNurbs(const PosedModel& a, const PosedModel& b, const QueryContext& ctx) {
  const auto& ma = static_cast<const NurbsModel&>(a.model);
  const auto& mb = static_cast<const NurbsModel&>(b.model);
  const Eigen::Isometry3d X_AB = a.X_WM.inverse() * b.X_WM;
  // A point of either model inside the other proves the overlap (apart surfaces overlap only so): the surface
  // search is spared (see insideSolid).
  if (const std::optional<Eigen::Vector3d> corner = firstCornerInside(ma, mb, X_AB))
    return ctx.overlapVerdictOnly ? overlapVerdict() : meeting(a, b, ctx, a.toWorld(*corner));
  PairSearch search(ma, mb, X_AB, ctx.tolerance, ctx.overlapVerdictOnly,
                    ctx.apartProofOnly ? kApartProofBudget : kPairBudget);
  const Outcome outcome = search.run();
  if (outcome == Outcome::Crossing) {
    if (ctx.overlapVerdictOnly) return overlapVerdict();
    if (ctx.apartProofOnly) return notProvedApart(search.best());
    return meeting(a, b, ctx, a.toWorld(*search.pointInside()));
  }
  // An exhausted search whose lower bound is still positive has proved the surfaces apart too.
  const bool surfacesApart = outcome != Outcome::Touching && search.lower() > 0;
  if (ctx.overlapVerdictOnly && outcome == Outcome::Touching)
    return !ctx.apartProofOnly && overlapWitnessed(a, b, ctx) ? overlapVerdict() : notProvedApart(search.best());
  // A search that ran out without proving the surfaces apart: the penetration search's test needs no more.
  if (ctx.apartProofOnly && !surfacesApart) return notProvedApart(search.best());
  // Touching or crossing: two convex solids go to EPA, which settles both; others try the escapes first, unless a
  // patch corner inside the other shows them crossing (the escapes' searches would then be spent for nothing).
  if (outcome == Outcome::Touching && !(convexSolid(ma) && convexSolid(mb)) && !cornerInside(ma, mb, X_AB))
    if (std::optional<DistanceResult> r = settleTouching(a, b, ctx, search))
      return *r;
  if (!surfacesApart) return meeting(a, b, ctx, a.toWorld(0.5 * (search.pointA() + search.pointB())));

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
  // Inside both patches the best pair is a stationary point of the distance; on a patch edge the local minimum
  // may lie across the seam, where the local projections follow it.
  if (search.bestOnPatchEdge()) polishAcrossPatches(a, b, r, ctx.tolerance, kSeamPolishShare * ctx.tolerance);
  return r;
}

}  // namespace unidist::detail
