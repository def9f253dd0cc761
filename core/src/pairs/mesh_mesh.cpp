#include "pairs/mesh_mesh.h"

#include "cloud/point_tree.h"
#include "generic/generic_distance.h"
#include "mesh/bvh.h"
#include "mesh/point_triangle.h"
#include "mesh/triangle_triangle.h"
#include "pairs/analytic.h"
#include "unidist/mesh.h"
#include "unidist/point_cloud.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace unidist::detail {
namespace {

/// One side of the search: its hierarchy, per-node balls and (meshes) per-node RSS.
struct Side {
  const mesh::Bvh* tree;
  const mesh::BigVector<BoundingSphere>* spheres;
  const mesh::BigVector<mesh::Rss>* rss = nullptr;
};

/// Best pair found so far, in A's frame.
struct Best {
  double distance = std::numeric_limits<double>::infinity();
  Eigen::Vector3d pA = Eigen::Vector3d::Zero(), pB = Eigen::Vector3d::Zero();
  int triA = -1;          ///< A's triangle (mesh) or point, for a normal at distance 0
  bool intersecting = false;
};

struct Traversal {
  double lowerBound = 0;  ///< proved lower bound on the minimum (before rounding slack)
  long leafPairs = 0;
  long nodePairs = 0;  ///< node pairs expanded or evaluated (leaf pairs included)
  bool exhausted = false;
};

/// B's node volumes turned into A's frame, each once, for a search that meets the same B nodes again and again
/// (linked torus_1k–torus_20k: ~22,000 RSS bounds meet ~350 of the 1k torus's nodes). The cache is made only
/// once the search has met as many node pairs as a quarter of B's nodes, so a short search never pays for it;
/// until then each volume is turned where it is needed.
class PosedVolumes {
 public:
  struct Box {
    Eigen::Vector3d center, half;
  };
  PosedVolumes(const mesh::Bvh& tree, const mesh::Rss* rss, const Eigen::Matrix3d& R, const Eigen::Vector3d& t)
      : nodes_(tree.nodes.data()), count_(tree.nodes.size()), rss_(rss), R_(R), absR_(R.cwiseAbs()), t_(t) {}

  /// An axis-aligned box in A's frame holding B's node j.
  Box box(std::uint32_t j, long nodePairs) {
    if (!ready(nodePairs)) return turnBox(j);
    std::uint32_t& slot = boxSlot_[j];
    if (slot == kNone) {
      slot = static_cast<std::uint32_t>(boxes_.size());
      boxes_.push_back(turnBox(j));
    }
    return boxes_[slot];
  }
  /// rssLowerBound(a, B's node j's RSS) (both have RSS volumes).
  double rssLowerBound(const mesh::Rss& a, std::uint32_t j, long nodePairs, double enough) {
    if (!ready(nodePairs)) return mesh::rssLowerBound(a, rss_[j], R_, t_, enough);
    std::uint32_t& slot = rssSlot_[j];
    if (slot == kNone) {
      slot = static_cast<std::uint32_t>(posed_.size());
      posed_.push_back(mesh::posedRss(rss_[j], R_, t_));
    }
    return mesh::rssLowerBound(a, posed_[slot], enough);
  }

 private:
  static constexpr std::uint32_t kNone = ~0u;
  Box turnBox(std::uint32_t j) const {
    const mesh::BvhNode& y = nodes_[j];
    return {R_ * y.center() + t_, absR_ * y.halfExtent()};
  }
  // Per node, where its turned volumes are (kNone: not yet): only the volumes met are ever written, so making
  // the cache costs two index arrays, not an array of volumes (env/rob: 40–176 node pairs in all).
  bool ready(long nodePairs) {
    if (!boxSlot_.empty()) return true;
    if (static_cast<std::size_t>(nodePairs) * 4 < count_) return false;
    boxSlot_.assign(count_, kNone);
    rssSlot_.assign(count_, kNone);
    return true;
  }
  const mesh::BvhNode* nodes_;
  const std::size_t count_;
  const mesh::Rss* rss_;
  const Eigen::Matrix3d R_, absR_;
  const Eigen::Vector3d t_;
  std::vector<std::uint32_t> boxSlot_, rssSlot_;
  std::vector<Box> boxes_;
  std::vector<mesh::Rss> posed_;
};

/// Best-first search over node pairs (a min-heap on the lower bound), pruning pairs whose lower bound is
/// within `prune` of the best distance. leaf(nodeA, nodeB, best, false) evaluates a leaf pair exactly;
/// leaf(nodeA, nodeB, best, true) measures only its nearest item pair (an upper bound to start from).
template <class LeafFn>
Traversal traverse(const Side& A, const Side& B, const Eigen::Isometry3d& X_AB, double prune, long budget, Best& best,
                   LeafFn&& leaf) {
  const mesh::BvhNode* na = A.tree->nodes.data();
  const mesh::BvhNode* nb = B.tree->nodes.data();
  const BoundingSphere* sa = A.spheres->data();
  const BoundingSphere* sb = B.spheres->data();
  const Eigen::Matrix3d R = X_AB.linear();
  const Eigen::Vector3d t = X_AB.translation();
  const mesh::Rss* ra = A.rss && B.rss ? A.rss->data() : nullptr;
  const mesh::Rss* rb = ra ? B.rss->data() : nullptr;

  Traversal out;
  PosedVolumes posedB(*B.tree, rb, R, t);
  // The cheap bounds: the gap between A's box and B's box turned into A's frame, and without RSS volumes the
  // ball–ball gap (with them the balls changed the node-pair count by under 1 % on the linked tori and the
  // env/rob poses, and cost 2 % of the time).
  auto cheapLower = [&](std::uint32_t i, std::uint32_t j) {
    const mesh::BvhNode& x = na[i];
    const PosedVolumes::Box y = posedB.box(j, out.nodePairs);
    const Eigen::Vector3d& c = y.center;
    const Eigen::Vector3d& h = y.half;
    double s = 0;
    for (int k = 0; k < 3; ++k) {
      const double below = x.lo[k] - (c[k] + h[k]), above = (c[k] - h[k]) - x.hi[k];
      const double g = below > 0 ? below : (above > 0 ? above : 0.0);
      s += g * g;
    }
    const double box = std::sqrt(s);
    if (ra) return box;
    const Eigen::Vector3d cb = R * sb[j].center + t;
    return std::max(box, (sa[i].center - cb).norm() - sa[i].radius - sb[j].radius);
  };

  struct Entry {
    std::uint32_t a, b;
    double lb;
    bool tight;  ///< lb includes the RSS bound (or there is none)
    bool operator<(const Entry& o) const { return lb > o.lb; }  // min-heap on the lower bound
  };
  // The RSS bound on top of the cheap ones (below `cutoff` only: above it the pair is pruned anyway).
  auto tighten = [&](Entry& e, double cutoff) {
    if (!e.tight && e.lb < cutoff) e.lb = std::max(e.lb, posedB.rssLowerBound(ra[e.a], e.b, out.nodePairs, cutoff));
    e.tight = true;
  };
  double minPruned = std::numeric_limits<double>::infinity();
  // The children pairs with the cheap bounds only: the RSS bound is added when a pair is taken up, so pairs
  // still queued when the search stops never pay for it.
  auto children = [&](const Entry& e, Entry& c0, Entry& c1) {
    const mesh::BvhNode& x = na[e.a];
    const mesh::BvhNode& y = nb[e.b];
    // Split the larger node (by ball radius) that is not a leaf.
    const bool splitA = !x.leaf() && (y.leaf() || sa[e.a].radius >= sb[e.b].radius);
    if (splitA) {
      c0 = {x.first, e.b, cheapLower(x.first, e.b), !ra};
      c1 = {x.first + 1, e.b, cheapLower(x.first + 1, e.b), !ra};
    } else {
      c0 = {e.a, y.first, cheapLower(e.a, y.first), !ra};
      c1 = {e.a, y.first + 1, cheapLower(e.a, y.first + 1), !ra};
    }
    if (c0.lb > c1.lb) std::swap(c0, c1);
  };
  // The heap holds at most kHeapCap pairs; further ones go on a stack taken first (depth first below the
  // best-first front). Measured on the linked tori, where tens of thousands of pairs fall below the best, the
  // heap operations had been a quarter of the time; ordinary poses never fill the heap.
  constexpr std::size_t kHeapCap = 512;
  std::vector<Entry> heap, stack;
  heap.reserve(256);
  auto bestFirst = [&] { return stack.empty() && heap.size() < kHeapCap; };
  auto queue = [&](const Entry& c) {
    if (heap.size() < kHeapCap) {
      heap.push_back(c);
      std::push_heap(heap.begin(), heap.end());
    } else {
      stack.push_back(c);
    }
  };
  // A first upper bound: the nearer child pair (cheap bounds) down to a leaf pair, and there the item pair of
  // smallest bound. Measured: without it the first pairs taken up pay the full RSS bound against an infinite
  // best (separated tori: twice the time); measuring that whole leaf pair had been most of the exact triangle
  // pairs at some env/rob poses (it is measured again in its turn).
  {
    Entry d{0, 0, 0.0, true};
    while (!(na[d.a].leaf() && nb[d.b].leaf())) {
      Entry c0, c1;
      children(d, c0, c1);
      d = c0;
      ++out.nodePairs;
    }
    ++out.leafPairs;
    leaf(d.a, d.b, best, true);
  }
  heap.push_back({0, 0, cheapLower(0, 0), !ra});
  Entry e{};
  bool diving = false;
  while (best.distance > 0) {
    bool fromHeap = false;
    if (!diving) {
      if (!stack.empty()) {
        e = stack.back();
        stack.pop_back();
      } else if (!heap.empty()) {
        std::pop_heap(heap.begin(), heap.end());
        e = heap.back();
        heap.pop_back();
        fromHeap = true;
      } else {
        break;
      }
    }
    diving = false;
    const double cutoff = best.distance - prune;
    if (e.lb >= cutoff) {
      minPruned = std::min(minPruned, e.lb);
      if (fromHeap) break;  // the smallest of the heap, and the stack is empty: every pair left is farther
      continue;
    }
    if (!e.tight) {
      tighten(e, cutoff);
      if (e.lb >= cutoff) {
        minPruned = std::min(minPruned, e.lb);
        continue;
      }
      if (fromHeap && !heap.empty() && e.lb > heap.front().lb) {  // no longer the smallest: back in line
        heap.push_back(e);
        std::push_heap(heap.begin(), heap.end());
        continue;
      }
    }
    if (out.leafPairs >= budget) {
      out.exhausted = true;
      minPruned = std::min(minPruned, e.lb);
      break;
    }
    ++out.nodePairs;
    if (na[e.a].leaf() && nb[e.b].leaf()) {
      ++out.leafPairs;
      leaf(e.a, e.b, best, false);
      continue;
    }
    Entry c[2];
    children(e, c[0], c[1]);
    if (c[1].lb < best.distance - prune)
      queue(c[1]);
    else
      minPruned = std::min(minPruned, c[1].lb);
    // Into the nearer child pair without a round trip through the heap when it is the nearest anyway (or
    // when no longer best first). Measured on env/rob: diving regardless reached far leaves before near ones
    // (and with it a quick descent to a first leaf pair, dropped: that pair was measured again in its turn),
    // 14–35 exact triangle pairs per query at poses 3 and 7 where this order needs 1–9.
    if (bestFirst() && !heap.empty() && c[0].lb > heap.front().lb) {
      queue(c[0]);
      continue;
    }
    e = c[0];
    diving = true;  // checked against the cutoff at the top of the loop
  }
  // Pairs left queued (the budget ran out, or the surfaces touch): their bounds still hold.
  for (const Entry& q : heap) minPruned = std::min(minPruned, q.lb);
  for (const Entry& q : stack) minPruned = std::min(minPruned, q.lb);
  out.lowerBound = std::min(minPruned, best.distance);
  return out;
}

/// Scale of the coordinates in the computation (for the rounding slack).
double coordinateScale(const Model& a, const Model& b, const Eigen::Isometry3d& X_AB) {
  const BoundingSphere sa = a.localBoundingSphere(), sb = b.localBoundingSphere();
  return sa.center.norm() + sa.radius + (X_AB * sb.center).norm() + sb.radius + sb.center.norm();
}

DistanceResult finish(const PosedModel& a, const Best& best, const Traversal& tr, double scale, const QueryContext& ctx,
                      const Eigen::Vector3d& zeroNormal_A, const char* method) {
  DistanceResult r;
  r.method = method;
  r.iterations = static_cast<int>(std::min<long>(tr.nodePairs, std::numeric_limits<int>::max()));
  r.pointA = a.toWorld(best.pA);
  r.pointB = a.toWorld(best.pB);
  const Eigen::Vector3d gap = r.pointB - r.pointA;
  const double g = gap.norm();
  if (best.distance > 0 && g > 0) {
    r.distance = g;
    r.normal = gap / g;
  } else {
    r.distance = 0;
    r.pointB = r.pointA;
    r.normal = a.dirToWorld(zeroNormal_A);
  }
  const double slack = roundingSlack(scale + r.distance);
  r.upperBound = r.distance + slack;
  r.lowerBound = std::max(0.0, std::min(tr.lowerBound, r.distance) - slack);
  if (r.distance == 0) r.lowerBound = 0, r.upperBound = 0;
  if (tr.exhausted) r.status = Status::Bounded;
  else settleStatus(r, ctx.tolerance);
  return r;
}

long budgetOf(const QueryContext& ctx) { return std::max<long>(1, static_cast<long>(ctx.maxIterations) * 16); }

double pruneOf(const QueryContext& ctx, double scale) {
  // Prune within the tolerance less the slack the bounds will lose to rounding.
  return std::max(0.0, 0.5 * ctx.tolerance - 2 * roundingSlack(scale));
}

/// Whether solid S contains any of the given points (in S's frame after X_SP).
bool solidContainsAny(const Model& solid, const std::vector<Eigen::Vector3d>& points, const Eigen::Isometry3d& X_SP) {
  const Aabb box = solid.localBounds();
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d q = X_SP * p;
    if ((q.array() < box.min.array()).any() || (q.array() > box.max.array()).any()) continue;
    if (solid.inside(q)) return true;
  }
  return false;
}

/// The generic routine for an overlap: distance <= 0 is proved by the touching/crossing surfaces.
DistanceResult overlap(const PosedModel& a, const PosedModel& b, const QueryContext& ctx, bool touching,
                       PairFn fn = nullptr) {
  if (ctx.overlapVerdictOnly) return overlapVerdict();
  DistanceResult r = fn ? fn(a, b, ctx) : genericPair(a, b, ctx);
  if (touching) {
    if (r.distance > 0) {
      r.distance = 0;
      r.pointB = r.pointA;
    }
    r.upperBound = std::min(r.upperBound, 0.0);
    r.lowerBound = std::min(r.lowerBound, r.upperBound);
    settleStatus(r, ctx.tolerance);
  }
  return r;
}

/// Leaf routine when B's items are points: B's leaf points move into A's frame once, then every A item (a
/// triangle or a point) is measured against each by closestOnA(item, q) → {point of the item, distance}.
template <class ClosestOnA>
auto pointLeaf(const mesh::Bvh& treeA, const mesh::Bvh& treeB, const std::vector<Eigen::Vector3d>& pointsB,
               const Eigen::Isometry3d& X_AB, ClosestOnA closestOnA) {
  return [&treeA, &treeB, &pointsB, X_AB, closestOnA](std::uint32_t i, std::uint32_t j, Best& bst, bool) {
    const mesh::BvhNode& x = treeA.nodes[i];
    const mesh::BvhNode& y = treeB.nodes[j];
    Eigen::Vector3d q[mesh::kMaxLeafSize];
    for (std::uint32_t l = 0; l < y.count; ++l) q[l] = X_AB * pointsB[treeB.order[y.first + l]];
    for (std::uint32_t m = 0; m < x.count; ++m) {
      const std::uint32_t item = treeA.order[x.first + m];
      for (std::uint32_t l = 0; l < y.count; ++l) {
        const auto [onA, d] = closestOnA(item, q[l]);
        if (d < bst.distance) {
          bst.distance = d;
          bst.pA = onA;
          bst.pB = q[l];
          bst.triA = static_cast<int>(item);
        }
      }
    }
  };
}

/// The leaf work of two meshes (B posed in A's frame): every triangle pair of a leaf pair gets a lower bound,
/// and the pairs below the best are measured exactly, nearest bound first, so the best drops early and prunes
/// the rest (measured: big triangles, as in FCL's env/rob, had made the exact routine most of the time).
class TrianglePairs {
 public:
  TrianglePairs(const TriangleMesh& ma, const TriangleMesh& mb, const mesh::MeshBvh& ha, const mesh::MeshBvh& hb,
                const Eigen::Isometry3d& X_AB)
      : ma_(ma), mb_(mb), ha_(ha), hb_(hb), X_AB_(X_AB), R_(X_AB.linear()) {}

  /// Leaf pair (i, j): bounds for each triangle pair, then the exact distance nearest bound first, each pair
  /// only while its bound is below the best (or only the first: `nearestOnly`).
  void operator()(std::uint32_t i, std::uint32_t j, Best& bst, bool nearestOnly) {
    const mesh::BvhNode& x = ha_.tree.nodes[i];
    const mesh::BvhNode& y = hb_.tree.nodes[j];
    // Consecutive leaf pairs mostly share one leaf (the search splits one side under a fixed other): its
    // triangles are kept from the previous call.
    if (i != leafA_) {
      for (std::uint32_t m = 0; m < x.count; ++m) A_[m] = ofA(x.first + m);
      leafA_ = i;
    }
    if (j != leafB_) {
      for (std::uint32_t l = 0; l < y.count; ++l) B_[l] = posedB(y.first + l);
      leafB_ = j;
    }
    const Posed* A = A_;
    const Posed* B = B_;
    struct Candidate {
      double lb;
      std::uint32_t m, l;
    };
    Candidate cand[mesh::kMaxLeafSize * mesh::kMaxLeafSize];
    int count = 0;
    const double cut = bst.distance;
    for (std::uint32_t m = 0; m < x.count; ++m)
      for (std::uint32_t l = 0; l < y.count; ++l) {
        const double lb = lowerBound(A[m], B[l], cut);
        if (lb >= cut) continue;
        int k = count++;
        for (; k > 0 && cand[k - 1].lb > lb; --k) cand[k] = cand[k - 1];  // insertion: ascending bounds
        cand[k] = {lb, m, l};
      }
    for (int k = 0; k < count && cand[k].lb < bst.distance; ++k) {
      if (edgeAxesApart(A[cand[k].m], B[cand[k].l], bst.distance)) continue;
      if (measure(A[cand[k].m], B[cand[k].l], bst) || nearestOnly) return;
    }
  }

 private:
  /// A triangle with what its pair bounds use: vertices, unit normal, box, centroid and offsets from it.
  struct Posed {
    Eigen::Vector3d v[3], n, lo, hi, c, off[3];
    int id;
  };

  static Posed make(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                    const Eigen::Vector3d& n, int id) {
    Posed t;
    t.v[0] = p0, t.v[1] = p1, t.v[2] = p2;
    t.n = n;
    t.lo = p0.cwiseMin(p1).cwiseMin(p2);
    t.hi = p0.cwiseMax(p1).cwiseMax(p2);
    t.c = (p0 + p1 + p2) / 3.0;
    for (int k = 0; k < 3; ++k) t.off[k] = t.v[k] - t.c;
    t.id = id;
    return t;
  }
  Posed ofA(std::uint32_t slot) const {
    const auto id = static_cast<int>(ha_.tree.order[slot]);
    const auto& tri = ma_.triangles()[id];
    const auto& v = ma_.vertices();
    return make(v[tri[0]], v[tri[1]], v[tri[2]], ma_.faceNormal(id), id);
  }
  Posed posedB(std::uint32_t slot) const {
    const auto id = static_cast<int>(hb_.tree.order[slot]);
    const auto& tri = mb_.triangles()[id];
    const auto& v = mb_.vertices();
    return make(X_AB_ * v[tri[0]], X_AB_ * v[tri[1]], X_AB_ * v[tri[2]], R_ * mb_.faceNormal(id), id);
  }

  /// A lower bound on the triangles' distance (or anything ≥ cut once it is proved ≥ cut): the gap of their
  /// boxes, along the line of their centroids (tight for triangles side by side at a distance) and along
  /// either normal (tight for facing ones).
  static double lowerBound(const Posed& a, const Posed& b, double cut) {
    const Eigen::Vector3d gap = (b.lo - a.hi).cwiseMax(a.lo - b.hi).cwiseMax(0.0);
    const double gg = gap.squaredNorm();
    if (gg >= cut * cut) return cut;
    double lb = std::sqrt(gg);
    const Eigen::Vector3d u = b.c - a.c;
    const double uu = u.squaredNorm();
    if (uu > 0) {
      // Gap along u, times |u|: compared squared before any square root (most pairs end here).
      const double reachA = std::max({u.dot(a.off[0]), u.dot(a.off[1]), u.dot(a.off[2])});
      const double reachB = std::min({u.dot(b.off[0]), u.dot(b.off[1]), u.dot(b.off[2])});
      const double scaled = uu + reachB - reachA;
      if (scaled > 0 && scaled * scaled >= cut * cut * uu) return cut;
      lb = std::max(lb, scaled / std::sqrt(uu));
    }
    return std::max({lb, slabGap(a.n, a.v[0], b.v), slabGap(b.n, b.v[0], a.v)});
  }
  /// Whether a direction across an edge of each triangle (edge × edge) proves them at least `cut` apart: the
  /// remaining separating directions after the boxes, centroid line and normals of lowerBound, exact for pairs
  /// closest edge to edge. Tried before the exact routine only (it costs a fifth of it): linked
  /// torus_1k–torus_20k, where nearly every pair measured lies 1e-3–1e-2 beyond the minimum, 29 % fewer
  /// instructions per query. Projections from the centroids, so far from the origin they stay accurate.
  static bool edgeAxesApart(const Posed& a, const Posed& b, double cut) {
    const Eigen::Vector3d d = b.c - a.c;
    const double cc = cut * cut;
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d ea = a.v[(i + 1) % 3] - a.v[i];
      for (int j = 0; j < 3; ++j) {
        const Eigen::Vector3d u = ea.cross(b.v[(j + 1) % 3] - b.v[j]);
        const double pa0 = u.dot(a.off[0]), pa1 = u.dot(a.off[1]), pa2 = u.dot(a.off[2]);
        const double ud = u.dot(d);
        const double pb0 = ud + u.dot(b.off[0]), pb1 = ud + u.dot(b.off[1]), pb2 = ud + u.dot(b.off[2]);
        const double gap = std::max(std::min({pb0, pb1, pb2}) - std::max({pa0, pa1, pa2}),
                                    std::min({pa0, pa1, pa2}) - std::max({pb0, pb1, pb2}));
        if (gap > 0 && gap * gap >= cc * u.squaredNorm()) return true;
      }
    }
    return false;
  }
  /// Gap between the plane through o with normal n and the triangle t (negative when it straddles).
  static double slabGap(const Eigen::Vector3d& n, const Eigen::Vector3d& o, const Eigen::Vector3d* t) {
    const double h0 = n.dot(t[0] - o), h1 = n.dot(t[1] - o), h2 = n.dot(t[2] - o);
    return std::max(std::min({h0, h1, h2}), -std::max({h0, h1, h2}));
  }
  /// Exact distance of the pair, kept when below the best; true when the triangles touch.
  static bool measure(const Posed& a, const Posed& b, Best& bst) {
    const mesh::TriangleTriangleClosest c = mesh::closestTriangleTriangle(a.v, a.n, b.v, b.n, bst.distance);
    if (!(c.distance < bst.distance)) return false;
    bst.distance = c.distance;
    bst.pA = c.pointA;
    bst.pB = c.pointB;
    bst.triA = a.id;
    bst.intersecting = c.intersecting;
    return c.distance <= 0;
  }

  const TriangleMesh& ma_;
  const TriangleMesh& mb_;
  const mesh::MeshBvh& ha_;
  const mesh::MeshBvh& hb_;
  const Eigen::Isometry3d X_AB_;
  const Eigen::Matrix3d R_;
  std::uint32_t leafA_ = ~0u, leafB_ = ~0u;  ///< the leaves A_ and B_ hold
  Posed A_[mesh::kMaxLeafSize], B_[mesh::kMaxLeafSize];
};

}  // namespace

DistanceResult meshMesh(const PosedModel& a, const PosedModel& b, const QueryContext& ctx, PairFn overlapFn) {
  const auto& ma = static_cast<const TriangleMesh&>(a.model);
  const auto& mb = static_cast<const TriangleMesh&>(b.model);
  const Eigen::Isometry3d X_AB = a.X_WM.inverse(Eigen::Isometry) * b.X_WM;
  const Eigen::Isometry3d X_BA = X_AB.inverse(Eigen::Isometry);
  const auto& va = ma.vertices();
  const auto& vb = mb.vertices();

  // The search runs in the frame of the mesh with more triangles (F) and turns the other's (P's) volumes and
  // leaves: the coarser side's leaves stay while the finer side's change, and its fewer nodes are met more
  // often (linked torus_1k–torus_20k with the 1k torus as the frame: 5,042 leaf loads turned, against 794).
  const bool swapped = mb.triangles().size() > ma.triangles().size();
  const TriangleMesh& mf = swapped ? mb : ma;
  const TriangleMesh& mp = swapped ? ma : mb;
  const Eigen::Isometry3d& X_FP = swapped ? X_BA : X_AB;
  const mesh::MeshBvh& hf = mf.bvh();
  const mesh::MeshBvh& hp = mp.bvh();
  // Rounding slack for the coordinates of both frames: the search's (F's) and the answer's (A's).
  const double scale = swapped ? std::max(coordinateScale(ma, mb, X_AB), coordinateScale(mf, mp, X_FP))
                               : coordinateScale(ma, mb, X_AB);

  Best best;  // in F's frame until the end
  TrianglePairs leaf(mf, mp, hf, hp, X_FP);
  const Side sideF{&hf.tree, &hf.spheres, &hf.rss(mf.vertices(), mf.triangles())};
  const Side sideP{&hp.tree, &hp.spheres, &hp.rss(mp.vertices(), mp.triangles())};
  Traversal tr = traverse(sideF, sideP, X_FP, pruneOf(ctx, scale), budgetOf(ctx), best, leaf);

  const bool solidA = ma.isSolid(), solidB = mb.isSolid();
  if ((solidA || solidB) && best.distance > 0 && !(tr.lowerBound > 0) && !tr.exhausted) {
    // Closer than the pruning allowance: the pairs pruned may cross, and one vertex's containment cannot tell
    // crossing surfaces from apart ones. Apart must be proved (a positive lower bound) first: search exactly.
    tr = traverse(sideF, sideP, X_FP, 0.0, budgetOf(ctx), best, leaf);
  }
  if (solidA || solidB) {
    if (best.distance <= 0) return overlap(a, b, ctx, true, overlapFn);
    // Apart surfaces: overlap only by containment (of a whole component when the other is open).
    if (solidA && (solidB ? ma.inside(X_AB * vb[0]) : solidContainsAny(ma, vb, X_AB))) return overlap(a, b, ctx, false, overlapFn);
    if (solidB && (solidA ? mb.inside(X_BA * va[0]) : solidContainsAny(mb, va, X_BA))) return overlap(a, b, ctx, false, overlapFn);
  }
  // Back into A's frame; at distance 0 the normal is F's face normal (B's turned into A's and reversed).
  Eigen::Vector3d zeroNormal = best.triA >= 0 ? mf.faceNormal(best.triA) : Eigen::Vector3d::UnitZ();
  if (swapped) {
    std::swap(best.pA, best.pB);
    best.pA = X_AB * best.pA;
    best.pB = X_AB * best.pB;
    if (best.triA >= 0) zeroNormal = -(X_AB.linear() * zeroNormal);
  }
  DistanceResult r = finish(a, best, tr, scale, ctx, zeroNormal, "mesh-mesh-bvh");
  if ((solidA || solidB) && !(tr.lowerBound > 0) && r.distance > 0) {  // the budget ran out before apart was proved
    r.lowerBound = -std::numeric_limits<double>::infinity();
    r.status = Status::Bounded;
  }
  return r;
}

DistanceResult meshCloud(const PosedModel& a, const PosedModel& b, const QueryContext& ctx) {
  const auto& ma = static_cast<const TriangleMesh&>(a.model);
  const auto& cb = static_cast<const PointCloud&>(b.model);
  const mesh::MeshBvh& ha = ma.bvh();
  const cloud::PointTree& hb = cb.tree();
  const Eigen::Isometry3d X_AB = a.X_WM.inverse(Eigen::Isometry) * b.X_WM;
  const double scale = coordinateScale(ma, cb, X_AB);
  const auto& va = ma.vertices();
  const auto& ta = ma.triangles();
  const auto& pb = cb.points();

  Best best;
  const auto leaf = pointLeaf(ha.tree, hb.tree, pb, X_AB, [&](std::uint32_t t, const Eigen::Vector3d& q) {
    const auto& tri = ta[t];
    const mesh::TriangleClosest c =
        mesh::closestOnTriangle(q, va[tri[0]], va[tri[1]], va[tri[2]], ma.faceNormal(static_cast<int>(t)));
    return std::pair<Eigen::Vector3d, double>(c.point, std::sqrt(c.squaredDistance));
  });
  const Traversal tr = traverse({&ha.tree, &ha.spheres}, {&hb.tree, &hb.spheres}, X_AB, pruneOf(ctx, scale),
                                budgetOf(ctx), best, leaf);
  if (ma.isSolid() && (best.distance <= 0 || solidContainsAny(ma, pb, X_AB))) return overlap(a, b, ctx, false);
  const Eigen::Vector3d zeroNormal = best.triA >= 0 ? ma.faceNormal(best.triA) : Eigen::Vector3d::UnitZ();
  return finish(a, best, tr, scale, ctx, zeroNormal, "mesh-cloud-bvh");
}

DistanceResult cloudCloud(const PosedModel& a, const PosedModel& b, const QueryContext& ctx) {
  const auto& ca = static_cast<const PointCloud&>(a.model);
  const auto& cb = static_cast<const PointCloud&>(b.model);
  const cloud::PointTree& ha = ca.tree();
  const cloud::PointTree& hb = cb.tree();
  const Eigen::Isometry3d X_AB = a.X_WM.inverse(Eigen::Isometry) * b.X_WM;
  const double scale = coordinateScale(ca, cb, X_AB);
  const auto& pa = ca.points();

  Best best;
  const auto leaf = pointLeaf(ha.tree, hb.tree, cb.points(), X_AB, [&](std::uint32_t p, const Eigen::Vector3d& q) {
    return std::pair<Eigen::Vector3d, double>(pa[p], (q - pa[p]).norm());
  });
  const Traversal tr = traverse({&ha.tree, &ha.spheres}, {&hb.tree, &hb.spheres}, X_AB, pruneOf(ctx, scale),
                                budgetOf(ctx), best, leaf);
  return finish(a, best, tr, scale, ctx, Eigen::Vector3d::UnitZ(), "cloud-cloud-bvh");
}

}  // namespace unidist::detail
