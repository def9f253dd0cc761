#include "mesh/bvh.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace unidist::mesh {
namespace {
constexpr std::uint32_t kRssScanBelow = 256;  // nodes up to this many triangles fit their RSS to their vertices

constexpr int kBins = 16;
constexpr int kSahDepth = 48;  // below this depth: median splits, which halve the count (depth bound)
constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr float kInfF = std::numeric_limits<float>::infinity();

// The split decisions work in single precision, four lanes at a time (the fourth lane is unused): they only
// steer the tree's shape. The nodes' boxes are computed afterwards, exactly, from the items' double boxes.
using Lane4 = Eigen::Array4f;

struct BoxF {
  Lane4 lo = Lane4::Constant(kInfF), hi = Lane4::Constant(-kInfF);
  void extend(const Lane4& l, const Lane4& h) {
    lo = lo.min(l);
    hi = hi.max(h);
  }
  void extend(const BoxF& b) { extend(b.lo, b.hi); }
  float area() const {
    const Lane4 d = (hi - lo).max(0.0f);
    return 2.0f * (d[0] * d[1] + d[1] * d[2] + d[2] * d[0]);
  }
};

struct Task {
  std::uint32_t node, begin, end;
  int depth;
  BoxF centroids;  // of the items in [begin, end), known from the parent's split
};

// The items are moved, not indexed, while building: every pass over a node's slots is then a sequential scan
// (an index array would make each of the ~log n passes over all items a random walk through memory).
struct WorkItem {
  Lane4 lo, hi;  // the fourth lanes are 0
  Lane4 centroid() const { return 0.5f * (lo + hi); }  // the box centre stands for the item
};

struct Work {
  std::vector<WorkItem> items;
  std::vector<std::uint32_t> ids;
  void swap(std::uint32_t i, std::uint32_t j) {
    std::swap(items[i], items[j]);
    std::swap(ids[i], ids[j]);
  }
  /// Moves the items for which `left` holds to the front of [b, e); returns the first of the others.
  template <class Pred>
  std::uint32_t partition(std::uint32_t b, std::uint32_t e, Pred left) {
    std::uint32_t i = b, j = e;
    for (;;) {
      while (i < j && left(items[i])) ++i;
      while (i < j && !left(items[j - 1])) --j;
      if (i >= j) return i;
      swap(i, j - 1);
      ++i;
      --j;
    }
  }
};

BoxF centroidBounds(const Work& w, std::uint32_t b, std::uint32_t e) {
  BoxF c;
  for (std::uint32_t i = b; i < e; ++i) {
    const Lane4 m = w.items[i].centroid();
    c.extend(m, m);
  }
  return c;
}

// Binned surface-area heuristic along `axis`: reorders slots [b, e) so that [b, mid) are the left items and
// returns mid with both children's centroid bounds, or returns e when no plane separates the items.
std::uint32_t sahSplit(Work& w, std::uint32_t b, std::uint32_t e, int axis, float cmin, float extent, Task& left,
                       Task& right) {
  // Fewer bins for small nodes: most nodes are small, and 16 bins for 8 items are mostly empty sweeps.
  const int bins = static_cast<int>(std::min<std::uint32_t>(kBins, std::max<std::uint32_t>(4, (e - b) / 2)));
  const float scale = static_cast<float>(bins) / extent;
  if (!std::isfinite(scale)) return e;
  const auto binOf = [&](const WorkItem& it) {
    const int k = static_cast<int>((0.5f * (it.lo[axis] + it.hi[axis]) - cmin) * scale);
    return std::min(std::max(k, 0), bins - 1);
  };
  BoxF boxes[kBins], cboxes[kBins];
  std::uint32_t counts[kBins] = {};
  for (std::uint32_t i = b; i < e; ++i) {
    const WorkItem& it = w.items[i];
    const int k = binOf(it);
    boxes[k].extend(it.lo, it.hi);
    const Lane4 m = it.centroid();
    cboxes[k].extend(m, m);
    ++counts[k];
  }
  // Right-to-left sweep: area and count of bins k..end; then left-to-right for the cost of each plane.
  float rightArea[kBins];
  std::uint32_t rightCount[kBins];
  BoxF acc;
  std::uint32_t n = 0;
  for (int k = bins - 1; k > 0; --k) {
    acc.extend(boxes[k]);
    n += counts[k];
    rightArea[k] = acc.area();
    rightCount[k] = n;
  }
  BoxF lbox;
  std::uint32_t leftCount = 0;
  float bestCost = kInfF;
  int bestPlane = -1;
  for (int k = 1; k < bins; ++k) {  // plane between bins k − 1 and k
    lbox.extend(boxes[k - 1]);
    leftCount += counts[k - 1];
    if (leftCount == 0 || rightCount[k] == 0) continue;
    const float cost = lbox.area() * static_cast<float>(leftCount) + rightArea[k] * static_cast<float>(rightCount[k]);
    if (cost < bestCost) {
      bestCost = cost;
      bestPlane = k;
    }
  }
  if (bestPlane < 0) return e;
  for (int k = 0; k < bins; ++k) (k < bestPlane ? left : right).centroids.extend(cboxes[k]);
  return w.partition(b, e, [&](const WorkItem& it) { return binOf(it) < bestPlane; });
}

}  // namespace

double paddedRadius(double largestDistance) {
  if (!(largestDistance > 0)) return 0.0;
  return largestDistance * (1.0 + 8.0 * kEps) + 4.0 * std::numeric_limits<double>::denorm_min();
}

Bvh buildBvh(const std::vector<BvhItem>& items, int maxLeafSize) {
  const auto n = static_cast<std::uint32_t>(items.size());
  Work w;
  w.items.resize(n);
  w.ids.resize(n);
  // Single precision relative to the centre of everything, so a small model far from its origin keeps its
  // detail (floats of raw coordinates near 1e4 would merge features 1e-3 apart).
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const BvhItem& it : items) {
    lo = lo.cwiseMin(it.lo);
    hi = hi.cwiseMax(it.hi);
  }
  const Eigen::Vector3d origin = n > 0 ? Eigen::Vector3d(0.5 * (lo + hi)) : Eigen::Vector3d::Zero();
  const auto lane = [&origin](const Eigen::Vector3d& v) {
    const Eigen::Vector3d r = v - origin;
    return Lane4(static_cast<float>(r.x()), static_cast<float>(r.y()), static_cast<float>(r.z()), 0.0f);
  };
  for (std::uint32_t i = 0; i < n; ++i) {
    w.items[i] = {lane(items[i].lo), lane(items[i].hi)};
    w.ids[i] = i;
  }
  Bvh bvh;
  bvh.nodes.reserve(n > 0 ? 2 * static_cast<std::size_t>(n) - 1 : 1);
  bvh.nodes.push_back(BvhNode{});
  std::vector<Task> tasks;
  tasks.push_back({0, 0, n, 0, centroidBounds(w, 0, n)});
  const auto leafMax = static_cast<std::uint32_t>(std::clamp(maxLeafSize, 1, kMaxLeafSize));
  while (!tasks.empty()) {
    const Task t = tasks.back();
    tasks.pop_back();
    bvh.depth = std::max(bvh.depth, t.depth);
    const std::uint32_t count = t.end - t.begin;
    if (count <= leafMax) {
      bvh.nodes[t.node].first = t.begin;
      bvh.nodes[t.node].count = count;
      continue;
    }
    int axis = 0;
    const Lane4 extent = t.centroids.hi - t.centroids.lo;
    if (extent[1] > extent[axis]) axis = 1;
    if (extent[2] > extent[axis]) axis = 2;
    const auto left = static_cast<std::uint32_t>(bvh.nodes.size());
    Task leftTask{left, t.begin, 0, t.depth + 1, {}}, rightTask{left + 1, 0, t.end, t.depth + 1, {}};
    std::uint32_t mid = t.end;
    if (extent[axis] > 0 && t.depth < kSahDepth)
      mid = sahSplit(w, t.begin, t.end, axis, t.centroids.lo[axis], extent[axis], leftTask, rightTask);
    if (mid <= t.begin || mid >= t.end) {
      // Median split: by the centroid along the axis, or by slot when all centroids coincide.
      mid = t.begin + count / 2;
      if (extent[axis] > 0) {
        std::vector<std::uint32_t> perm(count);
        for (std::uint32_t i = 0; i < count; ++i) perm[i] = t.begin + i;
        std::nth_element(perm.begin(), perm.begin() + (mid - t.begin), perm.end(), [&](std::uint32_t a, std::uint32_t b) {
          return w.items[a].lo[axis] + w.items[a].hi[axis] < w.items[b].lo[axis] + w.items[b].hi[axis];
        });
        std::vector<WorkItem> items2(count);
        std::vector<std::uint32_t> ids2(count);
        for (std::uint32_t i = 0; i < count; ++i) items2[i] = w.items[perm[i]], ids2[i] = w.ids[perm[i]];
        std::copy(items2.begin(), items2.end(), w.items.begin() + t.begin);
        std::copy(ids2.begin(), ids2.end(), w.ids.begin() + t.begin);
      }
      leftTask.centroids = centroidBounds(w, t.begin, mid);
      rightTask.centroids = centroidBounds(w, mid, t.end);
    }
    leftTask.end = mid;
    rightTask.begin = mid;
    bvh.nodes.push_back(BvhNode{});
    bvh.nodes.push_back(BvhNode{});
    bvh.nodes[t.node].first = left;
    bvh.nodes[t.node].count = 0;
    tasks.push_back(rightTask);
    tasks.push_back(leftTask);
  }
  bvh.nodes.shrink_to_fit();
  bvh.order = std::move(w.ids);
  // Exact boxes, bottom-up (children are stored after their parents): leaves from their items' double boxes.
  for (std::size_t i = bvh.nodes.size(); i-- > 0;) {
    BvhNode& node = bvh.nodes[i];
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    if (node.leaf()) {
      for (std::uint32_t s = node.first; s < node.first + node.count; ++s) {
        lo = lo.cwiseMin(items[bvh.order[s]].lo);
        hi = hi.cwiseMax(items[bvh.order[s]].hi);
      }
    } else {
      const BvhNode &a = bvh.nodes[node.first], &b = bvh.nodes[node.first + 1];
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(a.lo[k], b.lo[k]);
        hi[k] = std::max(a.hi[k], b.hi[k]);
      }
    }
    for (int k = 0; k < 3; ++k) {
      node.lo[k] = lo[k];
      node.hi[k] = hi[k];
    }
  }
  return bvh;
}

std::vector<std::array<std::uint32_t, 2>> nodeRanges(const Bvh& bvh) {
  std::vector<std::array<std::uint32_t, 2>> ranges(bvh.nodes.size());
  // Children are stored after their parent, so a reverse sweep sees them first.
  for (std::size_t i = bvh.nodes.size(); i-- > 0;) {
    const BvhNode& n = bvh.nodes[i];
    if (n.leaf())
      ranges[i] = {n.first, n.first + n.count};
    else
      ranges[i] = {ranges[n.first][0], ranges[n.first + 1][1]};
  }
  return ranges;
}

std::size_t MeshBvh::memoryBytes() const {
  const std::size_t rssBytes = rssFitted() ? lazyRss->volumes.capacity() * sizeof(Rss) : 0;
  return tree.memoryBytes() + spheres.capacity() * sizeof(BoundingSphere) + cones.capacity() * sizeof(NormalCone) +
         ranges.capacity() * sizeof(ranges[0]) + rssBytes;
}

const std::vector<Rss>& MeshBvh::rss(const std::vector<Eigen::Vector3d>& vertices,
                                     const std::vector<TriangleMesh::Triangle>& triangles) const {
  std::call_once(lazyRss->once, [&] {
    lazyRss->volumes = fitNodeRss(*this, vertices, triangles);
    lazyRss->ready.store(true, std::memory_order_release);
  });
  return lazyRss->volumes;
}

std::vector<Rss> fitNodeRss(const MeshBvh& bvh, const std::vector<Eigen::Vector3d>& vertices,
                            const std::vector<TriangleMesh::Triangle>& triangles) {
  // Axes: principal axes of the node's vertices (with repeats), from moments summed bottom-up (children are
  // stored after their parents, so a reverse sweep sees them first), about the root's centre.
  // Extents: small nodes scan their vertices; larger ones merge their children's volumes, O(1) each. Measured
  // on the linked 1k/20k and 20k/20k tori: scanning up to kRssScanBelow triangles visits 0.3 % more node pairs
  // than scanning every node (merging above 16 or 32: 8–11 % more), and keeps the fit O(n log kRssScanBelow).
  const std::size_t nodes = bvh.tree.nodes.size();
  std::vector<Rss> out(nodes);
  if (nodes == 0) return out;
  const Eigen::Vector3d origin = bvh.tree.nodes[0].center();
  struct Moments {
    double count = 0;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
  };
  std::vector<Moments> moments(nodes);
  // The vertices in slot order, once: every node's points are then one contiguous, sequentially scanned range.
  const std::vector<std::uint32_t>& order = bvh.tree.order;
  std::vector<Eigen::Vector3d> points(3 * order.size());
  for (std::size_t s = 0; s < order.size(); ++s)
    for (int k = 0; k < 3; ++k) points[3 * s + k] = vertices[triangles[order[s]][k]];
  for (std::size_t i = nodes; i-- > 0;) {
    const BvhNode& node = bvh.tree.nodes[i];
    const auto [begin, end] = bvh.ranges[i];
    const Eigen::Vector3d* p = points.data() + 3 * static_cast<std::size_t>(begin);
    const std::size_t n = 3 * static_cast<std::size_t>(end - begin);
    Moments& m = moments[i];
    if (node.leaf()) {
      for (std::size_t k = 0; k < n; ++k) {
        const Eigen::Vector3d d = p[k] - origin;
        m.count += 1;
        m.sum += d;
        m.outer.noalias() += d * d.transpose();
      }
    } else {
      const Moments &l = moments[node.first], &r = moments[node.first + 1];
      m.count = l.count + r.count;
      m.sum = l.sum + r.sum;
      m.outer = l.outer + r.outer;
    }
    const Eigen::Vector3d mean = m.sum / m.count;
    const Eigen::Matrix3d axes = principalAxes(m.outer / m.count - mean * mean.transpose());
    const bool scan = node.leaf() || end - begin <= kRssScanBelow;
    out[i] = scan ? fitRss(axes, p, n) : mergeRss(axes, out[node.first], out[node.first + 1]);
  }
  return out;
}

MeshBvh buildMeshBvh(const std::vector<Eigen::Vector3d>& vertices,
                     const std::vector<TriangleMesh::Triangle>& triangles,
                     const std::vector<Eigen::Vector3d>& faceNormals) {
  std::vector<BvhItem> items(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const Eigen::Vector3d& a = vertices[triangles[t][0]];
    const Eigen::Vector3d& b = vertices[triangles[t][1]];
    const Eigen::Vector3d& c = vertices[triangles[t][2]];
    items[t].lo = a.cwiseMin(b).cwiseMin(c);
    items[t].hi = a.cwiseMax(b).cwiseMax(c);
  }
  MeshBvh m;
  m.tree = buildBvh(items);
  m.ranges = nodeRanges(m.tree);
  const std::size_t nodes = m.tree.nodes.size();
  m.spheres.resize(nodes);
  m.cones.resize(nodes);

  // Small nodes (the many near the leaves) get their volumes from a scan of their own triangles; larger nodes
  // merge their children's volumes (looser, but O(1) each, so the whole pass is O(n)). Children are stored
  // after their parents, so a reverse sweep sees them first.
  constexpr std::uint32_t kScanBelow = 32;
  const std::vector<std::uint32_t>& order = m.tree.order;
  std::vector<Eigen::Vector3d> normalSums(nodes);
  for (std::size_t i = nodes; i-- > 0;) {
    const BvhNode& node = m.tree.nodes[i];
    const auto [begin, end] = m.ranges[i];
    const Eigen::Vector3d c = node.center();
    const bool scan = end - begin <= kScanBelow;
    // Ball: the largest distance from the box centre to a vertex of the node's triangles, or for a large
    // node the children's balls seen from this centre, and never more than the box's half diagonal.
    double reach = 0;
    if (scan) {
      double farthest = 0;
      for (std::uint32_t s = begin; s < end; ++s)
        for (std::uint32_t v : triangles[order[s]]) farthest = std::max(farthest, (vertices[v] - c).squaredNorm());
      reach = std::sqrt(farthest);
    } else {
      for (std::uint32_t child : {node.first, node.first + 1})
        reach = std::max(reach, (m.spheres[child].center - c).norm() + m.spheres[child].radius);
      const Eigen::Vector3d half(0.5 * (node.hi[0] - node.lo[0]), 0.5 * (node.hi[1] - node.lo[1]),
                                 0.5 * (node.hi[2] - node.lo[2]));
      // The stored centre is the true box centre up to its rounding (ε of its coordinates), hence the pad.
      reach = std::min(reach, half.norm() + 4.0 * kEps * c.cwiseAbs().sum());
    }
    m.spheres[i] = {c, paddedRadius(reach)};
    // Cone: the axis is the mean unit normal; a sum shorter than 1e-9 of the count means normals all around.
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    if (scan) {
      for (std::uint32_t s = begin; s < end; ++s) sum += faceNormals[order[s]];
    } else {
      sum = normalSums[node.first] + normalSums[node.first + 1];
    }
    normalSums[i] = sum;
    NormalCone& cone = m.cones[i];
    const double length = sum.norm();
    if (!(length > 1e-9 * static_cast<double>(end - begin))) {
      cone.axis = Eigen::Vector3d::UnitZ();
      cone.halfAngle = M_PI;
      continue;
    }
    cone.axis = sum / length;
    if (scan) {
      double lowest = 1.0;
      for (std::uint32_t s = begin; s < end; ++s) lowest = std::min(lowest, cone.axis.dot(faceNormals[order[s]]));
      // Padded so rounding of the dot products (a few ε) cannot leave a normal outside: acos turns an error δ
      // of the cosine into δ/sin θ, at most sqrt(2δ) < 1e-7 near θ = 0, and < 64ε where the cosine is below 0.9.
      const double pad = lowest > 0.9 ? 1e-7 : 64.0 * kEps;
      cone.halfAngle = std::min(M_PI, std::acos(std::max(-1.0, lowest)) + pad);
    } else {
      double half = 0;
      for (std::uint32_t child : {node.first, node.first + 1}) {
        const NormalCone& k = m.cones[child];
        half = std::max(half, std::atan2(cone.axis.cross(k.axis).norm(), cone.axis.dot(k.axis)) + k.halfAngle);
      }
      cone.halfAngle = std::min(M_PI, half + 64.0 * kEps);
    }
  }
  return m;
}

}  // namespace unidist::mesh
