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
  Lane4 lo, hi;  // not initialised: the bin arrays set only the bins a split uses (most splits use 4 of 16)
  static BoxF empty() { return {Lane4::Constant(kInfF), Lane4::Constant(-kInfF)}; }
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
  BoxF centroids = BoxF::empty();  // of the items in [begin, end), known from the parent's split
};

// The items are moved, not indexed, while building: every pass over a node's slots is then a sequential scan
// (an index array would make each of the ~log n passes over all items a random walk through memory).
struct WorkItem {
  Lane4 lo, hi;  // the fourth lanes are 0
  Lane4 centroid() const { return 0.5f * (lo + hi); }  // the box centre stands for the item
};

struct Work {
  BigVector<WorkItem> items;
  BigVector<std::uint32_t> ids;
  BigVector<std::uint8_t> bins;  // each item's bin in the split under way (binned once, read by the partition)
  void swap(std::uint32_t i, std::uint32_t j) {
    std::swap(items[i], items[j]);
    std::swap(ids[i], ids[j]);
    std::swap(bins[i], bins[j]);
  }
  /// Moves the items whose bin is below `plane` to the front of [b, e); returns the first of the others.
  std::uint32_t partitionByBin(std::uint32_t b, std::uint32_t e, std::uint8_t plane) {
    std::uint32_t i = b, j = e;
    for (;;) {
      while (i < j && bins[i] < plane) ++i;
      while (i < j && bins[j - 1] >= plane) --j;
      if (i >= j) return i;
      swap(i, j - 1);
      ++i;
      --j;
    }
  }
};

BoxF centroidBounds(const Work& w, std::uint32_t b, std::uint32_t e) {
  BoxF c = BoxF::empty();
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
  const auto binOf = [&](float centre) {
    const int k = static_cast<int>((centre - cmin) * scale);
    return std::min(std::max(k, 0), bins - 1);
  };
  // Two sets of bins for alternate items, merged after: neighbouring items mostly share a bin, and one set
  // would chain every update through the previous one's store (measured: 100k-triangle torus, tree build
  // 18.8 → 15.5 ms).
  BoxF boxes[kBins], cboxes[kBins], boxes2[kBins], cboxes2[kBins];
  std::uint32_t counts[kBins], counts2[kBins];
  for (int k = 0; k < bins; ++k) {
    boxes[k] = cboxes[k] = boxes2[k] = cboxes2[k] = BoxF::empty();
    counts[k] = counts2[k] = 0;
  }
  const auto add = [&](std::uint32_t i, BoxF* bx, BoxF* cb, std::uint32_t* cn) {
    const WorkItem& it = w.items[i];
    const Lane4 m = it.centroid();
    const int k = binOf(m[axis]);
    w.bins[i] = static_cast<std::uint8_t>(k);
    bx[k].extend(it.lo, it.hi);
    cb[k].extend(m, m);
    ++cn[k];
  };
  std::uint32_t i = b;
  for (; i + 1 < e; i += 2) {
    add(i, boxes, cboxes, counts);
    add(i + 1, boxes2, cboxes2, counts2);
  }
  if (i < e) add(i, boxes, cboxes, counts);
  for (int k = 0; k < bins; ++k) {
    boxes[k].extend(boxes2[k]);
    cboxes[k].extend(cboxes2[k]);
    counts[k] += counts2[k];
  }
  // Right-to-left sweep: area and count of bins k..end; then left-to-right for the cost of each plane.
  float rightArea[kBins];
  std::uint32_t rightCount[kBins];
  BoxF acc = BoxF::empty();
  std::uint32_t n = 0;
  for (int k = bins - 1; k > 0; --k) {
    acc.extend(boxes[k]);
    n += counts[k];
    rightArea[k] = acc.area();
    rightCount[k] = n;
  }
  BoxF lbox = BoxF::empty();
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
  return w.partitionByBin(b, e, static_cast<std::uint8_t>(bestPlane));
}

/// buildBvh over n items whose boxes boxOf(i) gives (three calls per item: meshes compute their triangles'
/// boxes from the corners instead of allocating a copy of every box).
template <class BoxOf>
Bvh buildBvhOf(std::uint32_t n, const BoxOf& boxOf, int maxLeafSize) {
  Work w;
  w.items.resize(n);
  w.ids.resize(n);
  w.bins.resize(n);
  // Single precision relative to the centre of everything, so a small model far from its origin keeps its
  // detail (floats of raw coordinates near 1e4 would merge features 1e-3 apart).
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::uint32_t i = 0; i < n; ++i) {
    const BvhItem it = boxOf(i);
    lo = lo.cwiseMin(it.lo);
    hi = hi.cwiseMax(it.hi);
  }
  const Eigen::Vector3d origin = n > 0 ? Eigen::Vector3d(0.5 * (lo + hi)) : Eigen::Vector3d::Zero();
  const auto lane = [&origin](const Eigen::Vector3d& v) {
    const Eigen::Vector3d r = v - origin;
    return Lane4(static_cast<float>(r.x()), static_cast<float>(r.y()), static_cast<float>(r.z()), 0.0f);
  };
  for (std::uint32_t i = 0; i < n; ++i) {
    const BvhItem it = boxOf(i);
    w.items[i] = {lane(it.lo), lane(it.hi)};
    w.ids[i] = i;
  }
  Bvh bvh;
  // The split pass records each node's (first, count) only; the nodes are made once their number is known. A
  // reserve of the worst case 2n − 1 full nodes, then shrunk, had copied every node into fresh pages (100k
  // triangles: ~12 % of the build on a machine where page faults are dear).
  struct Shape {
    std::uint32_t first = 0, count = 0;
  };
  BigVector<Shape> shape;
  shape.reserve(n > 0 ? 2 * static_cast<std::size_t>(n) - 1 : 1);
  shape.push_back(Shape{});
  std::vector<Task> tasks;
  tasks.push_back({0, 0, n, 0, centroidBounds(w, 0, n)});
  const auto leafMax = static_cast<std::uint32_t>(std::clamp(maxLeafSize, 1, kMaxLeafSize));
  while (!tasks.empty()) {
    const Task t = tasks.back();
    tasks.pop_back();
    bvh.depth = std::max(bvh.depth, t.depth);
    const std::uint32_t count = t.end - t.begin;
    if (count <= leafMax) {
      shape[t.node] = {t.begin, count};
      continue;
    }
    int axis = 0;
    const Lane4 extent = t.centroids.hi - t.centroids.lo;
    if (extent[1] > extent[axis]) axis = 1;
    if (extent[2] > extent[axis]) axis = 2;
    const auto left = static_cast<std::uint32_t>(shape.size());
    Task leftTask{left, t.begin, 0, t.depth + 1, BoxF::empty()},
        rightTask{left + 1, 0, t.end, t.depth + 1, BoxF::empty()};
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
    shape.push_back(Shape{});
    shape.push_back(Shape{});
    shape[t.node] = {left, 0};
    tasks.push_back(rightTask);
    tasks.push_back(leftTask);
  }
  bvh.nodes.resize(shape.size());
  for (std::size_t i = 0; i < shape.size(); ++i) {
    bvh.nodes[i].first = shape[i].first;
    bvh.nodes[i].count = shape[i].count;
  }
  BigVector<Shape>().swap(shape);
  bvh.order = std::move(w.ids);
  // Exact boxes, bottom-up (children are stored after their parents): leaves from their items' double boxes.
  for (std::size_t i = bvh.nodes.size(); i-- > 0;) {
    BvhNode& node = bvh.nodes[i];
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    if (node.leaf()) {
      for (std::uint32_t s = node.first; s < node.first + node.count; ++s) {
        const BvhItem it = boxOf(bvh.order[s]);
        lo = lo.cwiseMin(it.lo);
        hi = hi.cwiseMax(it.hi);
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

}  // namespace

double paddedRadius(double largestDistance) {
  if (!(largestDistance > 0)) return 0.0;
  return largestDistance * (1.0 + 8.0 * kEps) + 4.0 * std::numeric_limits<double>::denorm_min();
}

Bvh buildBvh(const std::vector<BvhItem>& items, int maxLeafSize) {
  return buildBvhOf(static_cast<std::uint32_t>(items.size()), [&items](std::uint32_t i) { return items[i]; }, maxLeafSize);
}

BigVector<std::array<std::uint32_t, 2>> nodeRanges(const Bvh& bvh) {
  BigVector<std::array<std::uint32_t, 2>> ranges(bvh.nodes.size());
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
  const std::size_t rssBytes = rssFitted() ? footprintBytes(lazyRss->volumes) : 0;
  return tree.memoryBytes() + footprintBytes(spheres) + footprintBytes(ranges) + rssBytes;
}

const BigVector<Rss>& MeshBvh::rss(const std::vector<Eigen::Vector3d>& vertices,
                                     const std::vector<TriangleMesh::Triangle>& triangles) const {
  std::call_once(lazyRss->once, [&] {
    lazyRss->volumes = fitNodeRss(*this, vertices, triangles);
    lazyRss->ready.store(true, std::memory_order_release);
  });
  return lazyRss->volumes;
}

namespace {

/// Walks the hierarchy children first (left subtree, right subtree, then the node), handing each node with at
/// most `pointsBelow` triangles the vertices of its triangles (each once per leaf: a vertex is shared by ~6
/// triangles, ~2 of them in the same leaf) as one contiguous array. The leaves come in slot order, so a node's
/// points are the end of one buffer from where its walk began; the buffer is cut back after every larger node,
/// so it stays a few kilobytes (cache-resident) instead of a copy of the mesh.
/// visit(node, points, count): points is null above pointsBelow.
template <class Visit>
void postOrderWithPoints(const Bvh& tree, const BigVector<std::array<std::uint32_t, 2>>& ranges,
                         const std::vector<Eigen::Vector3d>& vertices,
                         const std::vector<TriangleMesh::Triangle>& triangles, std::uint32_t pointsBelow,
                         Visit&& visit) {
  if (tree.nodes.empty()) return;
  struct Frame {
    std::uint32_t node;
    std::uint32_t pointsBegin;
    bool childrenDone;
  };
  Frame stack[kMaxBvhDepth + 4];
  int top = 0;
  std::vector<Eigen::Vector3d> points;
  // Room for a large node's two small children (three corners a triangle; never more than the mesh has);
  // it grows when large nodes further up still hold completed small children.
  points.reserve(std::min<std::size_t>(6 * static_cast<std::size_t>(pointsBelow), 3 * triangles.size()) + 16);
  stack[top++] = {0, 0, false};
  while (top > 0) {
    Frame& f = stack[top - 1];
    const BvhNode& node = tree.nodes[f.node];
    if (!node.leaf() && !f.childrenDone) {
      f.childrenDone = true;
      f.pointsBegin = static_cast<std::uint32_t>(points.size());
      stack[top++] = {node.first + 1, 0, false};
      stack[top++] = {node.first, 0, false};
      continue;
    }
    const Frame done = f;
    --top;
    if (node.leaf()) {
      const auto begin = static_cast<std::uint32_t>(points.size());
      std::uint32_t seen[3 * kMaxLeafSize];
      int distinct = 0;
      for (std::uint32_t k = 0; k < node.count; ++k)
        for (std::uint32_t v : triangles[tree.order[node.first + k]]) {
          if (std::find(seen, seen + distinct, v) != seen + distinct) continue;
          seen[distinct++] = v;
          points.push_back(vertices[v]);
        }
      visit(done.node, points.data() + begin, points.size() - begin);
      continue;
    }
    const auto& range = ranges[done.node];
    const bool small = range[1] - range[0] <= pointsBelow;
    visit(done.node, small ? points.data() + done.pointsBegin : nullptr, points.size() - done.pointsBegin);
    if (!small) points.resize(done.pointsBegin);
  }
}

/// Axes to start a leaf's principal-axis rotations from: its first triangle's edge and normal.
Eigen::Matrix3d leafGuess(const Bvh& tree, const BvhNode& leaf, const std::vector<Eigen::Vector3d>& vertices,
                          const std::vector<TriangleMesh::Triangle>& triangles) {
  const TriangleMesh::Triangle& t = triangles[tree.order[leaf.first]];
  const Eigen::Vector3d e0 = (vertices[t[1]] - vertices[t[0]]).normalized();
  const Eigen::Vector3d e2 = (vertices[t[1]] - vertices[t[0]]).cross(vertices[t[2]] - vertices[t[0]]).normalized();
  Eigen::Matrix3d U;
  U << e0, e2.cross(e0), e2;
  return U.allFinite() ? U : Eigen::Matrix3d::Identity();
}

/// First and second moments of a point set, about a fixed origin.
struct Moments {
  double count = 0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
  void add(const Eigen::Vector3d& d) {
    count += 1;
    sum += d;
    outer.noalias() += d * d.transpose();
  }
  void add(const Moments& o) {
    count += o.count;
    sum += o.sum;
    outer += o.outer;
  }
  Eigen::Matrix3d covariance() const {
    const Eigen::Vector3d mean = sum / count;
    return outer / count - mean * mean.transpose();
  }
};

}  // namespace

BigVector<Rss> fitNodeRss(const MeshBvh& bvh, const std::vector<Eigen::Vector3d>& vertices,
                            const std::vector<TriangleMesh::Triangle>& triangles) {
  // Axes: principal axes of the node's vertices (each once per leaf), from moments summed bottom-up about the
  // root's centre, by Jacobi rotations started from the larger child's axes (a leaf: from its first
  // triangle's frame). Extents: small nodes scan their vertices; larger ones merge their children's boxes,
  // O(1) each. Measured on the linked tori: scanning up to kRssScanBelow triangles visits ~0.4 % more node
  // pairs than scanning every node (up to 64: 2 %, 32: 6 %), and keeps the fit O(n log kRssScanBelow).
  const std::size_t nodes = bvh.tree.nodes.size();
  BigVector<Rss> out(nodes);
  if (nodes == 0) return out;
  const Eigen::Vector3d origin = bvh.tree.nodes[0].center();
  // The walk is children first, so a node's children's moments are the top two of this stack.
  Moments moments[kMaxBvhDepth + 4];
  int top = 0;
  postOrderWithPoints(bvh.tree, bvh.ranges, vertices, triangles, kRssScanBelow,
                      [&](std::uint32_t i, const Eigen::Vector3d* p, std::size_t n) {
                        const BvhNode& node = bvh.tree.nodes[i];
                        Eigen::Matrix3d guess;
                        Moments m;
                        if (node.leaf()) {
                          for (std::size_t k = 0; k < n; ++k) m.add(p[k] - origin);
                          guess = leafGuess(bvh.tree, node, vertices, triangles);
                        } else {
                          const Moments& l = moments[top - 2];
                          const Moments& r = moments[top - 1];
                          m = l;
                          m.add(r);
                          guess = out[l.count >= r.count ? node.first : node.first + 1].axes;
                          top -= 2;
                        }
                        moments[top++] = m;
                        const Eigen::Matrix3d axes = principalAxesFrom(m.covariance(), guess);
                        out[i] = p ? fitRss(axes, p, n) : mergeRss(axes, out[node.first], out[node.first + 1]);
                      });
  return out;
}

MeshBvh buildMeshBvh(const std::vector<Eigen::Vector3d>& vertices,
                     const std::vector<TriangleMesh::Triangle>& triangles) {
  const auto triangleBox = [&](std::uint32_t t) {
    const Eigen::Vector3d& a = vertices[triangles[t][0]];
    const Eigen::Vector3d& b = vertices[triangles[t][1]];
    const Eigen::Vector3d& c = vertices[triangles[t][2]];
    return BvhItem{a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c)};
  };
  MeshBvh m;
  m.tree = buildBvhOf(static_cast<std::uint32_t>(triangles.size()), triangleBox, kMaxLeafSize);
  m.ranges = nodeRanges(m.tree);
  m.spheres.resize(m.tree.nodes.size());

  // Balls, bottom-up (children are stored after their parents): a leaf's from the corners of its triangles,
  // an internal node's from its children's balls seen from its centre, never more than its box's half
  // diagonal. Scanning the vertices of nodes up to 32 triangles instead of merging their children changed the
  // node pairs the linked tori and env/rob visit by under 1 % and cost a second walk over the tree.
  for (std::size_t i = m.tree.nodes.size(); i-- > 0;) {
    const BvhNode& node = m.tree.nodes[i];
    const Eigen::Vector3d c = node.center();
    double reach = 0;
    if (node.leaf()) {
      double farthest = 0;
      for (std::uint32_t s = node.first; s < node.first + node.count; ++s)
        for (std::uint32_t v : triangles[m.tree.order[s]]) farthest = std::max(farthest, (vertices[v] - c).squaredNorm());
      reach = std::sqrt(farthest);
    } else {
      for (std::uint32_t child : {node.first, node.first + 1})
        reach = std::max(reach, (m.spheres[child].center - c).norm() + m.spheres[child].radius);
      // The stored centre is the true box centre up to its rounding (ε of its coordinates), hence the pad.
      reach = std::min(reach, node.halfExtent().norm() + 4.0 * kEps * c.cwiseAbs().sum());
    }
    m.spheres[i] = {c, paddedRadius(reach)};
  }
  return m;
}

}  // namespace unidist::mesh
