#include "mesh/mesh_topology.h"

#include "mesh/point_triangle.h"

#include <algorithm>
#include <numeric>

namespace unidist::mesh {
namespace {

// Compressed rows: for each key (a vertex id) the entries whose smallest vertex it is.
template <class Entry>
struct Buckets {
  std::vector<std::uint32_t> start;
  std::vector<Entry> entries;
};

template <class Entry, class KeyFn, class MakeFn>
Buckets<Entry> bucketBy(std::size_t keys, std::size_t items, KeyFn key, MakeFn make) {
  Buckets<Entry> b;
  b.start.assign(keys + 1, 0);
  for (std::size_t i = 0; i < items; ++i) ++b.start[key(i) + 1];
  std::partial_sum(b.start.begin(), b.start.end(), b.start.begin());
  b.entries.resize(items);
  std::vector<std::uint32_t> fill(b.start.begin(), b.start.end() - 1);
  for (std::size_t i = 0; i < items; ++i) b.entries[fill[key(i)]++] = make(i);
  return b;
}

}  // namespace

std::vector<std::uint32_t> weldExact(const std::vector<Eigen::Vector3d>& vertices, std::size_t& distinct) {
  const std::size_t n = vertices.size();
  std::vector<std::uint32_t> sorted(n);
  std::iota(sorted.begin(), sorted.end(), 0u);
  std::sort(sorted.begin(), sorted.end(), [&](std::uint32_t a, std::uint32_t b) {
    const Eigen::Vector3d &p = vertices[a], &q = vertices[b];
    if (p.x() != q.x()) return p.x() < q.x();
    if (p.y() != q.y()) return p.y() < q.y();
    if (p.z() != q.z()) return p.z() < q.z();
    return a < b;
  });
  // Representative of each vertex: the first (smallest index) of its group of equal positions.
  std::vector<std::uint32_t> rep(n);
  for (std::size_t i = 0; i < n;) {
    std::size_t j = i + 1;
    while (j < n && vertices[sorted[j]] == vertices[sorted[i]]) ++j;
    for (std::size_t k = i; k < j; ++k) rep[sorted[k]] = sorted[i];
    i = j;
  }
  std::vector<std::uint32_t> id(n);
  distinct = 0;
  for (std::size_t i = 0; i < n; ++i) id[i] = rep[i] == i ? static_cast<std::uint32_t>(distinct++) : id[rep[i]];
  return id;
}

std::vector<std::uint32_t> keptTriangles(const std::vector<Eigen::Vector3d>& vertices,
                                         const std::vector<Triangle>& triangles, std::size_t& zeroAreaCount,
                                         std::size_t& duplicates) {
  zeroAreaCount = duplicates = 0;
  std::vector<std::uint32_t> nonDegenerate;
  nonDegenerate.reserve(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const Triangle& tri = triangles[t];
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0] ||
        zeroArea(vertices[tri[0]], vertices[tri[1]], vertices[tri[2]])) {
      ++zeroAreaCount;
      continue;
    }
    nonDegenerate.push_back(static_cast<std::uint32_t>(t));
  }
  // Duplicates: the same sorted vertex triple. Bucket by the smallest vertex; buckets are small.
  struct Key {
    std::uint32_t mid, high, index;
  };
  std::vector<Triangle> sorted(nonDegenerate.size());
  for (std::size_t i = 0; i < nonDegenerate.size(); ++i) {
    sorted[i] = triangles[nonDegenerate[i]];
    std::sort(sorted[i].begin(), sorted[i].end());
  }
  const auto buckets = bucketBy<Key>(
      vertices.size(), nonDegenerate.size(), [&](std::size_t i) { return sorted[i][0]; },
      [&](std::size_t i) { return Key{sorted[i][1], sorted[i][2], static_cast<std::uint32_t>(i)}; });
  std::vector<std::uint8_t> drop(nonDegenerate.size(), 0);
  std::vector<Key> group;
  for (std::size_t v = 0; v < vertices.size(); ++v) {
    group.assign(buckets.entries.begin() + buckets.start[v], buckets.entries.begin() + buckets.start[v + 1]);
    if (group.size() < 2) continue;
    std::sort(group.begin(), group.end(), [](const Key& a, const Key& b) {
      if (a.mid != b.mid) return a.mid < b.mid;
      if (a.high != b.high) return a.high < b.high;
      return a.index < b.index;
    });
    for (std::size_t i = 1; i < group.size(); ++i)
      if (group[i].mid == group[i - 1].mid && group[i].high == group[i - 1].high) drop[group[i].index] = 1;
  }
  std::vector<std::uint32_t> kept;
  kept.reserve(nonDegenerate.size());
  for (std::size_t i = 0; i < nonDegenerate.size(); ++i) {
    if (drop[i])
      ++duplicates;
    else
      kept.push_back(nonDegenerate[i]);
  }
  return kept;
}

EdgeTopology buildEdgeTopology(std::size_t vertexCount, const std::vector<Triangle>& triangles) {
  EdgeTopology topo;
  const std::size_t halfEdges = 3 * triangles.size();
  topo.twin.assign(halfEdges, kNoTwin);
  const auto from = [&](std::size_t h) { return triangles[h / 3][h % 3]; };
  const auto to = [&](std::size_t h) { return triangles[h / 3][(h % 3 + 1) % 3]; };
  struct Entry {
    std::uint32_t other, halfEdge;
  };
  const auto buckets = bucketBy<Entry>(
      vertexCount, halfEdges, [&](std::size_t h) { return std::min(from(h), to(h)); },
      [&](std::size_t h) { return Entry{std::max(from(h), to(h)), static_cast<std::uint32_t>(h)}; });
  std::vector<Entry> group;
  for (std::size_t v = 0; v < vertexCount; ++v) {
    group.assign(buckets.entries.begin() + buckets.start[v], buckets.entries.begin() + buckets.start[v + 1]);
    std::sort(group.begin(), group.end(), [](const Entry& a, const Entry& b) {
      return a.other != b.other ? a.other < b.other : a.halfEdge < b.halfEdge;
    });
    for (std::size_t i = 0; i < group.size();) {
      std::size_t j = i + 1;
      while (j < group.size() && group[j].other == group[i].other) ++j;
      const std::size_t uses = j - i;
      ++topo.edges;
      std::size_t forward = 0;  // runs from the smaller vertex to the larger
      for (std::size_t k = i; k < j; ++k) forward += from(group[k].halfEdge) == v;
      if (uses == 1) {
        ++topo.boundary;
      } else if (uses == 2) {
        if (forward == 1) {
          topo.twin[group[i].halfEdge] = group[i + 1].halfEdge;
          topo.twin[group[i + 1].halfEdge] = group[i].halfEdge;
        } else {
          ++topo.misoriented;
        }
      } else {
        ++topo.nonManifold;
        if (2 * forward != uses) ++topo.misoriented;
      }
      i = j;
    }
  }
  return topo;
}

std::vector<std::uint32_t> fansPerVertex(std::size_t vertexCount, const std::vector<Triangle>& triangles,
                                         const std::vector<std::uint32_t>& twin) {
  std::vector<std::uint32_t> fans(vertexCount, 0);
  std::vector<std::uint8_t> visited(3 * triangles.size(), 0);
  for (std::size_t start = 0; start < visited.size(); ++start) {
    if (visited[start]) continue;
    const std::uint32_t v = triangles[start / 3][start % 3];
    ++fans[v];
    // Walk around v: from the corner (t, k) cross the edge entering the corner (from vertex k + 2 to v); its
    // twin leaves v in the next triangle, and its index is that triangle's corner at v.
    std::size_t corner = start;
    for (std::size_t steps = 0; steps < visited.size() && !visited[corner]; ++steps) {
      visited[corner] = 1;
      const std::size_t t = corner / 3, k = corner % 3;
      const std::uint32_t next = twin[3 * t + (k + 2) % 3];
      if (next == kNoTwin) break;
      corner = next;
    }
  }
  return fans;
}

std::size_t connectedComponents(std::size_t triangleCount, const std::vector<std::uint32_t>& twin) {
  std::vector<std::uint32_t> parent(triangleCount);
  std::iota(parent.begin(), parent.end(), 0u);
  const auto find = [&](std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  std::size_t components = triangleCount;
  for (std::size_t h = 0; h < twin.size(); ++h) {
    if (twin[h] == kNoTwin) continue;
    const std::uint32_t a = find(static_cast<std::uint32_t>(h / 3)), b = find(twin[h] / 3);
    if (a != b) {
      parent[a] = b;
      --components;
    }
  }
  return components;
}

double signedVolume(const std::vector<Eigen::Vector3d>& vertices, const std::vector<Triangle>& triangles,
                    const Eigen::Vector3d& origin) {
  double sum = 0;
  for (const Triangle& t : triangles) {
    const Eigen::Vector3d a = vertices[t[0]] - origin, b = vertices[t[1]] - origin, c = vertices[t[2]] - origin;
    sum += a.dot(b.cross(c));
  }
  return sum / 6.0;
}

}  // namespace unidist::mesh
