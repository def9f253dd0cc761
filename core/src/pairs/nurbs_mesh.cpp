#include "pairs/nurbs_mesh.h"

#include "convex/gjk.h"
#include "generic/generic_distance.h"
#include "mesh/bvh.h"
#include "mesh/point_triangle.h"
#include "nurbs/objectives.h"
#include "nurbs/patch_search.h"
#include "nurbs/patch_tree.h"
#include "unidist/mesh.h"
#include "unidist/nurbs.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <queue>
#include <vector>

namespace unidist::detail {

namespace {

constexpr int kHullGjkCap = 200;     // GJK on two small hulls converges in a few iterations; a guard only
constexpr int kMaxPatchDepth = 40;   // beyond this, rounding and not the bound limits the nodes
constexpr int kPairBudget = 20000;   // pairs popped before the search answers with the bounds it has
constexpr double kFlatAngle = 0.5;   // a patch node with a narrower normal cone is polished by Newton when popped
constexpr double kInf = std::numeric_limits<double>::infinity();

using Node = nurbs::PatchNode;
using Points = std::vector<Eigen::Vector3d>;

enum class Outcome { Proved, Touching, Exhausted };

struct OpenPair {
  double lower;
  const Node* a;
  std::uint32_t b;         // mesh BVH node
  Eigen::Vector3d wB;      // GJK's closest point on B's side (A's frame)
  bool operator>(const OpenPair& o) const { return lower > o.lower; }
};

/// Best-first over (patch node, mesh node) pairs in A's (the NURBS model's) frame.
class NurbsMeshSearch {
 public:
  NurbsMeshSearch(const NurbsModel& a, const TriangleMesh& b, const Eigen::Isometry3d& X_AB, double tolerance,
                  bool stopWhenApart)
      : a_(a), b_(b), bvh_(b.bvh()), X_AB_(X_AB), tolerance_(tolerance), stopWhenApart_(stopWhenApart),
        size_(a.localBounds().diagonal()), bothSolid_(a.isSolid() && b.isSolid()) {}

  Outcome run() {
    seed();
    for (const auto& root : a_.forest().roots) visit(root.get(), 0);
    int popped = 0;
    while (!open_.empty()) {
      const OpenPair top = open_.top();
      if (best_ <= 0.5 * tolerance_ || overlapProved_) return Outcome::Touching;
      if (top.lower >= best_ - 0.5 * tolerance_ || (stopWhenApart_ && lower() > 0)) return Outcome::Proved;
      if (popped >= kPairBudget) return Outcome::Exhausted;
      open_.pop();
      ++popped;
      ++iterations_;
      const mesh::BvhNode& nb = bvh_.tree.nodes[top.b];
      if (nb.leaf()) measureLeaf(*top.a, nb, top.wB);
      // Overlapping hulls of two solids: a corner of the subpatch inside the mesh proves the interiors meet,
      // long before the search would realise a crossing of the surfaces.
      if (bothSolid_ && top.lower <= 0) measureAgainstMesh(top.a->corners[0]);
      const bool splitMesh =
          !nb.leaf() && (top.a->depth >= kMaxPatchDepth || top.a->ball.radius < bvh_.spheres[top.b].radius);
      if (splitMesh) {
        visit(top.a, nb.first);
        visit(top.a, nb.first + 1);
      } else if (top.a->depth >= kMaxPatchDepth) {
        lowerOfClosed_ = std::min(lowerOfClosed_, top.lower);
      } else {
        for (const Node* c : a_.forest().children(*top.a, arena_)) visit(c, top.b);
      }
    }
    return best_ <= 0.5 * tolerance_ ? Outcome::Touching : Outcome::Proved;
  }

  double best() const { return best_; }
  double lower() const {
    const double open = open_.empty() ? kInf : open_.top().lower;
    return std::min({open, lowerOfClosed_, lowerOfPruned_, best_});
  }
  const Eigen::Vector3d& pointA() const { return pA_; }
  const Eigen::Vector3d& pointB() const { return pB_; }
  int iterations() const { return iterations_; }
  /// A mesh vertex in A's frame (for containment tests).
  Eigen::Vector3d vertex(std::uint32_t v) const { return X_AB_ * b_.vertices()[v]; }

 private:
  void offer(const Eigen::Vector3d& onA, const Eigen::Vector3d& onB) {
    const double d = (onB - onA).norm();
    if (d < best_) {
      best_ = d;
      pA_ = onA;
      pB_ = onB;
    }
  }

  /// A surface point against the mesh (its BVH search): a realised upper bound; with two solids, a point of
  /// A's surface strictly inside B (beyond rounding) proves that their interiors meet.
  void measureAgainstMesh(const Eigen::Vector3d& p) {
    const SurfacePoint s = b_.closestPoint(X_AB_.inverse() * p);
    offer(p, X_AB_ * s.point);
    const double rounding = 64 * std::numeric_limits<double>::epsilon() * (p.norm() + size_);
    if (bothSolid_ && s.signedDistance < -rounding) overlapProved_ = true;
  }

  /// Every root patch's corners against the mesh: an upper bound before the search starts.
  void seed() {
    for (const auto& root : a_.forest().roots)
      for (const Eigen::Vector3d& c : root->corners) measureAgainstMesh(c);
  }

  std::array<Eigen::Vector3d, 3> triangle(std::uint32_t slot) const {
    const auto& t = b_.triangles()[bvh_.tree.order[slot]];
    return {vertex(t[0]), vertex(t[1]), vertex(t[2])};
  }

  /// The nearest point of the leaf's triangles to p (A's frame), and its squared distance.
  double nearestInLeaf(const mesh::BvhNode& leaf, const Eigen::Vector3d& p, Eigen::Vector3d& onB) const {
    double bestSq = kInf;
    onB = p;
    for (std::uint32_t slot = leaf.first; slot < leaf.first + leaf.count; ++slot) {
      const auto t = triangle(slot);
      const mesh::TriangleClosest c = mesh::closestOnTriangle(p, t[0], t[1], t[2]);
      if (c.squaredDistance < bestSq) {
        bestSq = c.squaredDistance;
        onB = c.point;
      }
    }
    return bestSq;
  }

  /// Realised upper bounds at a popped pair with a mesh leaf: the node's corners, and on a flat node Newton on
  /// the patch toward GJK's witness on the triangles, then back onto the triangles, twice (alternating
  /// projection converges fast on a flat piece).
  void measureLeaf(const Node& na, const mesh::BvhNode& leaf, const Eigen::Vector3d& witnessB) {
    Eigen::Vector3d onB = witnessB;
    for (const Eigen::Vector3d& c : na.corners) {
      nearestInLeaf(leaf, c, onB);
      offer(c, onB);
    }
    if (na.normal.all || na.normal.angle > kFlatAngle) return;
    const RationalBezierPatch& patch = a_.patches()[static_cast<std::size_t>(na.patch)];
    Eigen::Vector3d target = witnessB;
    double s = 0.5 * (na.s0 + na.s1), t = 0.5 * (na.t0 + na.t1);
    for (int round = 0; round < 2; ++round) {
      const nurbs::PointObjective toward(target, size_);
      const nurbs::PatchHit h = nurbs::polish(patch, na.patch, toward, s, t);
      s = h.s;
      t = h.t;
      nearestInLeaf(leaf, h.point, onB);
      offer(h.point, onB);
      target = onB;
    }
  }

  void visit(const Node* na, std::uint32_t nb) {
    const BoundingSphere& sb = bvh_.spheres[nb];
    const Eigen::Vector3d cb = X_AB_ * sb.center;
    // Rounding of the subdivided nets and of the moved mesh: 256 ulps of the coordinates, as for the balls.
    const double eps = 256 * std::numeric_limits<double>::epsilon();
    const double margin = eps * (na->ball.center.norm() + na->ball.radius + cb.norm() + sb.radius);
    const double byBalls = (cb - na->ball.center).norm() - na->ball.radius - sb.radius - margin;
    if (byBalls >= best_ - 0.5 * tolerance_) {
      lowerOfPruned_ = std::min(lowerOfPruned_, byBalls);
      return;
    }
    // A closest pair with its point inside the patch has the segment normal to the surface there (or, on a patch
    // edge, orthogonal to the edge); the mesh side obeys no such rule at its edges and vertices.
    const nurbs::Cone towards = nurbs::coneTowards(cb, na->ball.center, na->ball.radius + sb.radius);
    if (!nurbs::mayHoldCritical(*na, towards, true)) return;
    const mesh::BvhNode& n = bvh_.tree.nodes[nb];
    double lower = kInf;
    Eigen::Vector3d witness = cb;
    auto hullBound = [&](const Points& other) {
      // Surfaces are at distance >= 0: EPA on overlapping hulls would measure nothing useful.
      const ConvexDistance c = convexDistance(supportOfPointSet(na->points), supportOfPointSet(other), 0.25 * tolerance_, kHullGjkCap, false);
      iterations_ += c.iterations;
      const double l = std::min(c.lowerBound, c.distance) - margin;
      if (l < lower) {
        lower = l;
        witness = c.pointB;
      }
    };
    if (n.leaf()) {
      for (std::uint32_t slot = n.first; slot < n.first + n.count; ++slot) {
        const auto t = triangle(slot);
        hullB_.assign(t.begin(), t.end());
        hullBound(hullB_);
      }
    } else {
      hullB_.clear();
      for (int k = 0; k < 8; ++k)
        hullB_.push_back(X_AB_ * Eigen::Vector3d(k & 1 ? n.hi[0] : n.lo[0], k & 2 ? n.hi[1] : n.lo[1],
                                                 k & 4 ? n.hi[2] : n.lo[2]));
      hullBound(hullB_);
    }
    if (lower >= best_ - 0.5 * tolerance_) {
      lowerOfPruned_ = std::min(lowerOfPruned_, lower);
      return;
    }
    open_.push({lower, na, nb, witness});
  }

  const NurbsModel& a_;
  const TriangleMesh& b_;
  const mesh::MeshBvh& bvh_;
  Eigen::Isometry3d X_AB_;
  double tolerance_;
  bool stopWhenApart_;
  double size_;
  bool bothSolid_;
  bool overlapProved_ = false;
  double best_ = kInf;
  Eigen::Vector3d pA_ = Eigen::Vector3d::Zero(), pB_ = Eigen::Vector3d::Zero();
  double lowerOfClosed_ = kInf;  // pairs at the depth cap
  double lowerOfPruned_ = kInf;  // pairs dropped by their bound
  int iterations_ = 0;
  Points hullB_;
  std::vector<std::unique_ptr<Node>> arena_;
  std::priority_queue<OpenPair, std::vector<OpenPair>, std::greater<OpenPair>> open_;
};

/// What the contract answers when the models' surfaces are within the tolerance: two open surfaces are simply
/// that close (their unsigned distance); with an inside on either side the generic routine decides the sign.
DistanceResult touchingOpenSurfaces(const PosedModel& a, const NurbsMeshSearch& s, double tolerance) {
  DistanceResult r = separationFromPoints(a, s.pointA(), s.pointB(), Eigen::Vector3d::UnitZ(), 0.0, s.iterations(),
                                          "nurbs-mesh-cones-gjk", tolerance);
  r.lowerBound = 0;
  settleStatus(r, tolerance);
  return r;
}

}  // namespace

DistanceResult nurbsMesh(const PosedModel& a, const PosedModel& b, const QueryContext& ctx) {
  const auto& ma = static_cast<const NurbsModel&>(a.model);
  const auto& mb = static_cast<const TriangleMesh&>(b.model);
  const Eigen::Isometry3d X_AB = a.X_WM.inverse() * b.X_WM;
  NurbsMeshSearch search(ma, mb, X_AB, ctx.tolerance, ctx.overlapVerdictOnly);
  // A point of either model inside the other proves the overlap: the surface search is spared (see insideSolid).
  const Eigen::Vector3d cornerA = ma.forest().roots.front()->corners[0];
  if (insideSolid(mb, X_AB.inverse() * cornerA) || insideSolid(ma, search.vertex(0)))
    return ctx.overlapVerdictOnly ? overlapVerdict() : genericPair(a, b, ctx);
  const Outcome outcome = search.run();
  const bool anInside = ma.isSolid() || mb.isSolid();
  if (outcome == Outcome::Touching) {
    if (!anInside) return touchingOpenSurfaces(a, search, ctx.tolerance);
    return ctx.overlapVerdictOnly ? notProvedApart(search.best()) : genericPair(a, b, ctx);
  }
  // Apart surfaces overlap only by containment, ruled out above.
  const bool surfacesApart = search.lower() > 0;
  if (!surfacesApart && !ctx.overlapVerdictOnly) return genericPair(a, b, ctx);  // exhausted, unresolved
  return separationFromPoints(a, search.pointA(), search.pointB(), Eigen::Vector3d::UnitZ(), search.lower(),
                              search.iterations(), "nurbs-mesh-cones-gjk", ctx.tolerance);
}

}  // namespace unidist::detail
