#include "pairs/nurbs_cloud.h"

#include "cloud/point_tree.h"
#include "generic/generic_distance.h"
#include "nurbs/hull_distance.h"
#include "nurbs/patch_tree.h"
#include "unidist/nurbs.h"
#include "unidist/point_cloud.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <unordered_map>
#include <vector>

namespace unidist::detail {
namespace {

constexpr int kHullGjkCap = 200;    // GJK on two small hulls converges in a few iterations; a guard only
constexpr int kMaxPatchDepth = 40;  // beyond this, rounding and not the bound limits the nodes
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEps = std::numeric_limits<double>::epsilon();
// The point query's side is reliable down to its own rounding (a few ulps of the coordinates × the model size,
// nurbs_sign_test.cpp); a point closer than this to the surface, moved into A's frame, is on it.
constexpr double kUnsureSide = 64 * kEps;

using Node = nurbs::PatchNode;

/// One cloud point's NURBS point query (A's frame).
struct PointValue {
  Eigen::Vector3d point, onSurface, normal;
  double signedDistance, error;  // the true distance lies in [|signedDistance| − error, |signedDistance|]
};

/// The cloud seen from the NURBS model's frame, and every point query made on it (each point at most once).
class CloudField {
 public:
  CloudField(const NurbsModel& a, const PointCloud& b, const Eigen::Isometry3d& X_AB)
      : a_(a), b_(b), tree_(b.tree()), X_AB_(X_AB), size_(a.localBounds().diagonal()) {}

  const NurbsModel& nurbs() const { return a_; }
  const cloud::PointTree& tree() const { return tree_; }
  const mesh::BvhNode& node(std::uint32_t n) const { return tree_.tree.nodes[n]; }
  const Eigen::Isometry3d& X_AB() const { return X_AB_; }
  double size() const { return size_; }
  int queries() const { return queries_; }
  const std::vector<Eigen::Vector3d>& pointsB() const { return b_.points(); }
  /// The point at a tree slot, in B's frame and in A's.
  const Eigen::Vector3d& pointB(std::uint32_t slot) const { return b_.points()[tree_.tree.order[slot]]; }
  Eigen::Vector3d pointA(std::uint32_t slot) const { return X_AB_ * pointB(slot); }
  /// A node's ball in A's frame, widened for the rounding of the move (256 ulps of the coordinates).
  BoundingSphere ball(std::uint32_t n) const {
    const BoundingSphere& s = tree_.spheres[n];
    const Eigen::Vector3d c = X_AB_ * s.center;
    return {c, s.radius + 256 * kEps * (c.norm() + s.center.norm() + s.radius)};
  }
  SurfacePoint query(const Eigen::Vector3d& q_A) {
    ++queries_;
    return a_.closestPoint(q_A);
  }
  /// The query of the point at a tree slot (made once).
  const PointValue& at(std::uint32_t slot) { return ofPoint(tree_.tree.order[slot]); }
  /// The query of point `index` of the cloud (made once).
  const PointValue& ofPoint(std::uint32_t index) {
    const auto found = values_.find(index);
    if (found != values_.end()) return found->second;
    const Eigen::Vector3d p = X_AB_ * b_.points()[index];
    const SurfacePoint s = query(p);
    return values_[index] = {p, s.point, s.normal, s.signedDistance, s.error};
  }

 private:
  const NurbsModel& a_;
  const PointCloud& b_;
  const cloud::PointTree& tree_;
  Eigen::Isometry3d X_AB_;
  double size_;
  int queries_ = 0;
  std::unordered_map<std::uint32_t, PointValue> values_;
};

/// Solid NURBS: are cloud points inside, and if so how deep is the deepest (the answer is minus that depth)?
/// One best-first search over cloud nodes on a proved lower bound of their points' signed distance: nodes not yet
/// placed (bounded through their parent's centre query: the signed distance is 1-Lipschitz) and nodes proved
/// inside (bounded by minus a surface point's distance plus the radius). The deepest regions come first, so
/// once a point is found inside, the nodes near the surface that cannot hold a deeper one are dropped unsplit.
class InsideSearch {
 public:
  InsideSearch(CloudField& field, double tolerance, int budget)
      : f_(field), tolerance_(tolerance), budget_(budget), box_(field.nurbs().localBounds()) {}

  /// false when the budget ran out.
  bool run() {
    open_.push({-kInf, 0, Eigen::Vector3d::Zero(), State::Unplaced});
    while (!open_.empty()) {
      Entry top = open_.top();
      // Every node left is outside (no inside point yet), or cannot beat the deepest by half the tolerance.
      if (best_ ? top.lower >= best_->signedDistance + best_->error - 0.5 * tolerance_ : top.lower > 0) return true;
      if (f_.queries() >= budget_) return false;
      open_.pop();
      if (top.state == State::Unplaced) place(top);
      else refineInside(top);
    }
    return true;
  }
  const PointValue* deepestPoint() const { return best_; }
  /// Proved: the signed distance of every cloud point is at least this (valid once a point is inside).
  double lower() const {
    const double open = open_.empty() ? kInf : open_.top().lower;
    return std::min({open, lowerOfDropped_, best_ ? best_->signedDistance : kInf});
  }
  /// Proved: some cloud point's signed distance is at most this.
  double upper() const { return best_ ? best_->signedDistance + best_->error : kInf; }

 private:
  enum class State { Unplaced, Inside, InsideTight };  // tight: bounded by its own centre query
  struct Entry {
    double lower;               // proved: every point of the node has at least this signed distance
    std::uint32_t node;
    Eigen::Vector3d onSurface;  // inside nodes: a surface point, so depth(p) <= |p − onSurface|
    State state;
    bool operator<(const Entry& o) const { return lower > o.lower; }  // min-heap on the bound
  };

  void offerPoint(const PointValue& v) {
    if (v.signedDistance < 0 && (!best_ || v.signedDistance < best_->signedDistance)) best_ = &v;
  }
  /// A node not yet known to lie on one side: outside the control points' box (so the solid), clear of the
  /// surface by its centre's query (then one side for all), or split; a leaf's points are queried.
  void place(const Entry& e) {
    const BoundingSphere b = f_.ball(e.node);
    if (box_.distanceTo(b.center) > b.radius) return;
    const mesh::BvhNode& n = f_.node(e.node);
    if (n.leaf()) {
      for (std::uint32_t s = n.first; s < n.first + n.count; ++s) offerPoint(f_.at(s));
      return;
    }
    const SurfacePoint c = f_.query(b.center);
    const double d = std::abs(c.signedDistance);
    if (d - c.error > b.radius) {
      if (c.signedDistance < 0) open_.push({-(d + b.radius), e.node, c.point, State::InsideTight});
      return;
    }
    const double lower = c.signedDistance - c.error - b.radius;
    open_.push({lower, n.first, c.point, State::Unplaced});
    open_.push({lower, n.first + 1, c.point, State::Unplaced});
  }
  /// An inside node: a leaf's points are queried unless their distance to the node's surface point already
  /// shows them no deeper than the best; a node bounded through its parent gets its own centre query first.
  void refineInside(Entry e) {
    const mesh::BvhNode& n = f_.node(e.node);
    const double enough = best_ ? -upper() + 0.5 * tolerance_ : 0.0;
    if (n.leaf()) {
      for (std::uint32_t s = n.first; s < n.first + n.count; ++s) {
        const double reach = (f_.pointA(s) - e.onSurface).norm();
        if (reach <= enough) lowerOfDropped_ = std::min(lowerOfDropped_, -reach);
        else offerPoint(f_.at(s));
      }
    } else if (e.state == State::Inside) {
      const BoundingSphere b = f_.ball(e.node);
      const SurfacePoint c = f_.query(b.center);
      e.lower = std::max(e.lower, -(std::abs(c.signedDistance) + b.radius));
      e.onSurface = c.point;
      e.state = State::InsideTight;
      open_.push(e);
    } else {
      for (const std::uint32_t child : {n.first, n.first + 1}) {
        const BoundingSphere b = f_.ball(child);
        open_.push({-((b.center - e.onSurface).norm() + b.radius), child, e.onSurface, State::Inside});
      }
    }
  }

  CloudField& f_;
  double tolerance_;
  int budget_;
  Aabb box_;
  const PointValue* best_ = nullptr;  // the deepest inside point queried (values live in the field's map)
  double lowerOfDropped_ = kInf;      // points an inside leaf dropped unqueried
  std::priority_queue<Entry> open_;
};

struct OpenPair {
  double lower;
  const Node* a;
  std::uint32_t b;  // cloud tree node
  bool operator>(const OpenPair& o) const { return lower > o.lower; }
};

/// Unsigned minimum distance from the cloud's points to the surface: best-first over (patch node, cloud node).
class SurfaceSearch {
 public:
  SurfaceSearch(CloudField& field, double tolerance, int budget)
      : f_(field), tolerance_(tolerance), budget_(budget), leafDone_(field.tree().tree.nodes.size(), 0) {}

  /// false when the budget ran out.
  bool run() {
    seed();
    for (const auto& root : f_.nurbs().forest().roots) visit(root.get(), 0);
    while (!open_.empty()) {
      const OpenPair top = open_.top();
      if (top.lower >= bestDistance() - 0.5 * tolerance_) return true;
      if (pops_ + f_.queries() >= budget_) return false;
      open_.pop();
      ++pops_;
      if (leafDone_[top.b]) continue;  // its points' own bounds stand for it
      const mesh::BvhNode& nb = f_.node(top.b);
      const double rb = f_.tree().spheres[top.b].radius;
      const bool patchAtCap = top.a->depth >= kMaxPatchDepth;
      if (nb.leaf() && (patchAtCap || top.a->ball.radius <= rb + std::max(0.0, top.lower))) {
        queryLeaf(top.b);
      } else if (!nb.leaf() && (patchAtCap || top.a->ball.radius < rb)) {
        visit(top.a, nb.first);
        visit(top.a, nb.first + 1);
      } else {
        for (const Node* c : f_.nurbs().forest().children(*top.a, arena_)) visit(c, top.b);
      }
    }
    return true;
  }

  const PointValue* closest() const { return best_; }
  double bestDistance() const { return best_ ? std::abs(best_->signedDistance) : kInf; }
  double lower() const {
    const double open = open_.empty() ? kInf : open_.top().lower;
    return std::min({open, lowerOfPruned_, lowerOfQueried_, bestDistance()});
  }
  int pops() const { return pops_; }

 private:
  void offer(const PointValue& v) {
    lowerOfQueried_ = std::min(lowerOfQueried_, std::abs(v.signedDistance) - v.error);
    if (std::abs(v.signedDistance) < bestDistance()) best_ = &v;
  }
  void queryLeaf(std::uint32_t leaf) {
    const mesh::BvhNode& n = f_.node(leaf);
    for (std::uint32_t s = n.first; s < n.first + n.count; ++s) offer(f_.at(s));
    leafDone_[leaf] = 1;
  }
  /// A first upper bound: the cloud point nearest to any root patch corner, queried.
  void seed() {
    const Eigen::Isometry3d X_BA = f_.X_AB().inverse();
    double nearest = kInf;
    std::uint32_t closestIndex = 0;
    for (const auto& root : f_.nurbs().forest().roots)
      for (const Eigen::Vector3d& c : root->corners) {
        double squared = 0;
        const std::uint32_t index = cloud::nearestPoint(f_.tree(), f_.pointsB(), X_BA * c, squared);
        if (squared < nearest) nearest = squared, closestIndex = index;
      }
    offer(f_.ofPoint(closestIndex));
  }

  void visit(const Node* na, std::uint32_t nb) {
    const BoundingSphere b = f_.ball(nb);
    const double margin = 256 * kEps * (na->ball.center.norm() + na->ball.radius + b.center.norm() + b.radius);
    const double cut = bestDistance() - 0.5 * tolerance_;
    const double byBalls = (b.center - na->ball.center).norm() - na->ball.radius - b.radius - margin;
    if (byBalls >= cut) {
      lowerOfPruned_ = std::min(lowerOfPruned_, byBalls);
      return;
    }
    // A point's closest surface point is a critical point of its distance: the segment is normal to the surface
    // there (or orthogonal to the patch edge it lies on).
    const nurbs::Cone towards = nurbs::coneTowards(b.center, na->ball.center, na->ball.radius + b.radius);
    if (!nurbs::mayHoldCritical(*na, towards, true)) return;
    const mesh::BvhNode& n = f_.node(nb);
    hullB_.clear();
    if (n.leaf()) {
      for (std::uint32_t s = n.first; s < n.first + n.count; ++s) hullB_.push_back(f_.pointB(s));
    } else {
      for (int k = 0; k < 8; ++k)
        hullB_.emplace_back(k & 1 ? n.hi[0] : n.lo[0], k & 2 ? n.hi[1] : n.lo[1], k & 4 ? n.hi[2] : n.lo[2]);
    }
    const nurbs::HullDistance h = nurbs::hullDistance(na->points, hullB_, f_.X_AB(), na->points.front(),
                                                      f_.X_AB() * hullB_.front(), 0.25 * tolerance_, kHullGjkCap,
                                                      cut + margin);
    const double lower = h.lower - margin;
    if (lower >= cut) {
      lowerOfPruned_ = std::min(lowerOfPruned_, lower);
      return;
    }
    open_.push({lower, na, nb});
  }

  CloudField& f_;
  double tolerance_;
  int budget_;
  int pops_ = 0;
  std::vector<char> leafDone_;  // per cloud node: its points are queried
  const PointValue* best_ = nullptr;
  double lowerOfPruned_ = kInf;   // pairs dropped by their bound
  double lowerOfQueried_ = kInf;  // the queried points' own lower bounds
  std::vector<Eigen::Vector3d> hullB_;
  std::vector<std::unique_ptr<Node>> arena_;
  std::priority_queue<OpenPair, std::vector<OpenPair>, std::greater<OpenPair>> open_;
};

/// The answer from the deepest point inside and its surface point (A's frame): minus its depth.
DistanceResult insideAnswer(const PosedModel& a, const PointValue& v, double lower, double upper, int iterations,
                            double tolerance) {
  DistanceResult r;
  r.method = "nurbs-cloud-bvh";
  r.iterations = iterations;
  r.pointA = a.toWorld(v.onSurface);
  r.pointB = a.toWorld(v.point);
  r.distance = v.signedDistance;
  // From an inside point the query's normal points toward the surface: the way the cloud leaves the solid.
  r.normal = a.dirToWorld(v.normal);
  r.upperBound = std::max(upper, r.distance);
  r.lowerBound = std::min(lower, r.distance);
  settleStatus(r, tolerance);
  return r;
}

}  // namespace

DistanceResult nurbsCloud(const PosedModel& a, const PosedModel& b, const QueryContext& ctx) {
  const auto& ma = static_cast<const NurbsModel&>(a.model);
  const auto& cb = static_cast<const PointCloud&>(b.model);
  CloudField field(ma, cb, a.X_WM.inverse(Eigen::Isometry) * b.X_WM);
  const int budget = std::max(1, ctx.maxIterations);
  if (ma.isSolid()) {
    InsideSearch inside(field, ctx.tolerance, budget);
    const bool done = inside.run();
    // Points inside only by rounding: the generic routine decides (as nurbs_mesh does for touching solids).
    if (inside.deepestPoint() && -inside.deepestPoint()->signedDistance <= kUnsureSide * field.size())
      return genericPair(a, b, ctx);
    if (inside.deepestPoint()) {
      DistanceResult r = insideAnswer(a, *inside.deepestPoint(), inside.lower(), inside.upper(), field.queries(),
                                      ctx.tolerance);
      if (!done) r.status = Status::Bounded;
      return r;
    }
    if (!done) {
      DistanceResult r;  // nothing realised yet: no finite bound either way
      r.method = "nurbs-cloud-bvh";
      r.distance = 0;
      r.lowerBound = -kInf;
      r.upperBound = kInf;
      r.status = Status::Bounded;
      return r;
    }
  }
  SurfaceSearch search(field, ctx.tolerance, budget);
  const bool done = search.run();
  const PointValue& v = *search.closest();
  DistanceResult r = separationFromPoints(a, v.onSurface, v.point, v.normal, std::max(0.0, search.lower()),
                                          field.queries() + search.pops(), "nurbs-cloud-bvh", ctx.tolerance);
  if (!done) r.status = Status::Bounded;
  return r;
}

}  // namespace unidist::detail
