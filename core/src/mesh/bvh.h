// Bounding volume hierarchy over boxed items (triangles of a mesh, points of a cloud), and the extra per-node
// volumes a mesh keeps. Internal.
//
// Layout: one flat array of nodes, the root first; an internal node's children are adjacent (first and
// first + 1), a leaf holds `count` consecutive slots of `order` (slot → item). Every node is a contiguous slot
// range, so "is item x below node n" is a range test on the slot of x.
//
// Build (top-down, iterative, O(n log n)): binned surface-area heuristic on the items' box centres along the
// axis of largest centre extent (16 bins), leaves of at most 4 items; below depth 48 (never reached on sane
// input) or when all centres coincide it splits at the median instead, so the depth stays below 48 + 32 and
// the fixed traversal stacks cannot overflow. The split decisions run in single precision on a compact copy
// of the items that is moved (not indexed) while splitting, so every pass is a sequential scan; the nodes'
// boxes are then computed exactly, bottom-up, from the items' double boxes. Measured against a Morton-order
// (LBVH) build: ~2× the build time, but 20–25 % fewer leaves visited by point queries.
//
// Bounding volumes: every node has an exact AABB of its items (tight, computed from the items' boxes). The
// mesh hierarchy adds per node, in parallel arrays so further volume types (OBB, RSS for mesh–mesh searches)
// can be added the same way without touching the others:
//  * a ball centred at the AABB centre, padded by a few ulps: a leaf's radius is the largest distance to a
//    corner of its triangles (a triangle is the hull of its vertices), an internal node's reaches its
//    children's balls (capped by the box's half diagonal), so it provably holds every triangle below;
//  * the node's slot range;
//  * a rectangle swept sphere (RSS, mesh/rss.h) holding the node's triangles, for mesh–mesh pair bounds (fitted
//    to the vertices; above 256 triangles merged from the children). Fitted lazily by rss(), on the first
//    mesh–mesh query, once and thread-safe: point-query-only use never pays for it.
// (Per-node normal cones are not kept: the normal cone search of contacts() builds its own, widened ones.)
// Which volume prunes point queries best was measured (tests/bench/mesh_build.cpp, docs in the report): the
// AABB alone, the ball alone, or the larger of the two lower bounds. The AABB is used.
#pragma once

#include "mesh/big_array.h"
#include "mesh/rss.h"
#include "unidist/mesh.h"

#include <Eigen/Core>

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

namespace unidist::mesh {

struct BvhNode {
  double lo[3], hi[3];
  std::uint32_t first;  ///< leaf: first slot of `order`; internal: the left child (the right one is first + 1)
  std::uint32_t count;  ///< leaf: number of items (> 0); internal: 0

  bool leaf() const { return count != 0; }
  /// Squared distance from q to the box (0 inside).
  double squaredDistance(const Eigen::Vector3d& q) const {
    double s = 0;
    for (int i = 0; i < 3; ++i) {
      const double below = lo[i] - q[i], above = q[i] - hi[i];
      const double g = below > 0 ? below : (above > 0 ? above : 0.0);
      s += g * g;
    }
    return s;
  }
  bool contains(const Eigen::Vector3d& q) const {
    return q.x() >= lo[0] && q.x() <= hi[0] && q.y() >= lo[1] && q.y() <= hi[1] && q.z() >= lo[2] && q.z() <= hi[2];
  }
  Eigen::Vector3d center() const {
    return {0.5 * lo[0] + 0.5 * hi[0], 0.5 * lo[1] + 0.5 * hi[1], 0.5 * lo[2] + 0.5 * hi[2]};
  }
  Eigen::Vector3d halfExtent() const { return {0.5 * (hi[0] - lo[0]), 0.5 * (hi[1] - lo[1]), 0.5 * (hi[2] - lo[2])}; }
};

/// An item to build over: its box (its centre is the point the build sorts it by).
struct BvhItem {
  Eigen::Vector3d lo, hi;
};

struct Bvh {
  BigVector<BvhNode> nodes;         ///< nodes[0] is the root
  BigVector<std::uint32_t> order;   ///< slot → item
  int depth = 0;                      ///< deepest leaf (root = 0)
  std::size_t memoryBytes() const { return footprintBytes(nodes) + footprintBytes(order); }
};

/// Deepest a tree built by buildBvh can be, so traversal stacks of this size never overflow.
constexpr int kMaxBvhDepth = 96;

/// Most items a leaf holds; leaf-pair routines size their scratch arrays by it.
constexpr int kMaxLeafSize = 4;

/// Builds the hierarchy with leaves of at most maxLeafSize (<= kMaxLeafSize) items.
Bvh buildBvh(const std::vector<BvhItem>& items, int maxLeafSize = kMaxLeafSize);

/// Slot range [begin, end) of every node (computed bottom-up from the leaves).
BigVector<std::array<std::uint32_t, 2>> nodeRanges(const Bvh& bvh);

/// Depth-first nearest-item search: visits the nearer child first and skips every node whose box is not
/// closer than the best squared distance so far. `leaf(firstSlot, count, bestSq)` tests the items and lowers
/// bestSq when it finds a closer one. Deterministic: the same q always visits the same nodes in the same order.
template <class LeafFn>
void nearestSearch(const Bvh& bvh, const Eigen::Vector3d& q, double& bestSq, LeafFn&& leaf) {
  struct Entry {
    std::uint32_t node;
    double squaredDistance;
  };
  Entry stack[kMaxBvhDepth + 4];
  int top = 0;
  const BvhNode* nodes = bvh.nodes.data();
  std::uint32_t current = 0;
  if (!(nodes[0].squaredDistance(q) < bestSq)) return;
  for (;;) {
    const BvhNode& n = nodes[current];
    if (n.leaf()) {
      leaf(n.first, n.count, bestSq);
    } else {
      std::uint32_t near = n.first, far = n.first + 1;
      double dNear = nodes[near].squaredDistance(q), dFar = nodes[far].squaredDistance(q);
      if (dFar < dNear) {
        std::swap(near, far);
        std::swap(dNear, dFar);
      }
      if (dNear < bestSq) {
        if (dFar < bestSq) stack[top++] = {far, dFar};
        current = near;
        continue;
      }
    }
    // Next pending node still closer than the best (the best may have improved since it was pushed).
    bool found = false;
    while (top > 0) {
      const Entry e = stack[--top];
      if (e.squaredDistance < bestSq) {
        current = e.node;
        found = true;
        break;
      }
    }
    if (!found) return;
  }
}

/// A cone of directions (the contacts' normal cone search uses it).
struct NormalCone {
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  double halfAngle = 0;  ///< radians; π = every direction
};

/// The hierarchy a triangle mesh keeps (see the top of this file).
struct MeshBvh {
  Bvh tree;
  BigVector<BoundingSphere> spheres;                 ///< per node
  BigVector<std::array<std::uint32_t, 2>> ranges;    ///< per node: slots [begin, end)
  std::size_t memoryBytes() const;

  /// Per node RSS, fitted on the first call (from the mesh this hierarchy was built for). Thread-safe.
  const BigVector<Rss>& rss(const std::vector<Eigen::Vector3d>& vertices,
                              const std::vector<TriangleMesh::Triangle>& triangles) const;
  bool rssFitted() const { return lazyRss->ready.load(std::memory_order_acquire); }

 private:
  struct LazyRss {
    std::once_flag once;
    std::atomic<bool> ready{false};
    BigVector<Rss> volumes;
  };
  std::unique_ptr<LazyRss> lazyRss = std::make_unique<LazyRss>();  // behind a pointer: MeshBvh stays movable
};

/// Fits the RSS of every node of `bvh` (the work MeshBvh::rss does once).
BigVector<Rss> fitNodeRss(const MeshBvh& bvh, const std::vector<Eigen::Vector3d>& vertices,
                            const std::vector<TriangleMesh::Triangle>& triangles);

MeshBvh buildMeshBvh(const std::vector<Eigen::Vector3d>& vertices,
                     const std::vector<TriangleMesh::Triangle>& triangles);

/// Ball centred at `center` holding every point given (radius = the largest distance, padded a few ulps
/// so the rounding of the distances cannot make it too small).
double paddedRadius(double largestDistance);

}  // namespace unidist::mesh
