#include "mesh/winding.h"

#include "mesh/mesh_topology.h"

#include <cmath>

namespace unidist::mesh {

std::size_t WindingData::memoryBytes() const {
  return edgeStart.capacity() * sizeof(std::uint32_t) + useBoundary.capacity() + edges.capacity() * sizeof(edges[0]);
}

WindingData buildWindingData(const MeshBvh& bvh, const std::vector<TriangleMesh::Triangle>& triangles,
                             const std::vector<std::uint32_t>& twin) {
  const auto& nodes = bvh.tree.nodes;
  const auto& order = bvh.tree.order;
  std::vector<std::uint32_t> slotOf(order.size());
  for (std::uint32_t s = 0; s < order.size(); ++s) slotOf[order[s]] = s;

  WindingData data;
  data.edgeStart.assign(nodes.size() + 1, 0);
  data.useBoundary.assign(nodes.size(), 0);
  std::vector<std::array<std::uint32_t, 2>> boundary;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    data.edgeStart[i] = static_cast<std::uint32_t>(data.edges.size());
    if (nodes[i].leaf()) continue;
    const auto [begin, end] = bvh.ranges[i];
    const std::size_t count = end - begin;
    boundary.clear();
    bool keep = true;
    for (std::uint32_t s = begin; s < end && keep; ++s) {
      const std::uint32_t t = order[s];
      for (std::uint32_t k = 0; k < 3; ++k) {
        const std::uint32_t tw = twin[3 * t + k];
        if (tw != kNoTwin && slotOf[tw / 3] >= begin && slotOf[tw / 3] < end) continue;  // cancels inside
        boundary.push_back({triangles[t][k], triangles[t][(k + 1) % 3]});
      }
      keep = boundary.size() < count;
    }
    if (!keep) continue;
    data.useBoundary[i] = 1;
    data.edges.insert(data.edges.end(), boundary.begin(), boundary.end());
  }
  data.edgeStart[nodes.size()] = static_cast<std::uint32_t>(data.edges.size());
  data.edges.shrink_to_fit();
  return data;
}

double solidAngle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double la = a.norm(), lb = b.norm(), lc = c.norm();
  const double numerator = a.dot(b.cross(c));
  const double denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
  return 2.0 * std::atan2(numerator, denominator);
}

double windingNumber(const Eigen::Vector3d& q, const MeshBvh& bvh, const WindingData& data,
                     const std::vector<Eigen::Vector3d>& vertices,
                     const std::vector<TriangleMesh::Triangle>& triangles) {
  const auto& nodes = bvh.tree.nodes;
  std::uint32_t stack[kMaxBvhDepth + 4];
  int top = 0;
  stack[top++] = 0;
  double sum = 0;
  while (top > 0) {
    const std::uint32_t i = stack[--top];
    const BvhNode& n = nodes[i];
    if (data.useBoundary[i] && !n.contains(q)) {
      const Eigen::Vector3d apex = n.center() - q;
      for (std::uint32_t e = data.edgeStart[i]; e < data.edgeStart[i + 1]; ++e)
        sum += solidAngle(apex, vertices[data.edges[e][0]] - q, vertices[data.edges[e][1]] - q);
    } else if (n.leaf()) {
      for (std::uint32_t s = n.first; s < n.first + n.count; ++s) {
        const TriangleMesh::Triangle& t = triangles[bvh.tree.order[s]];
        sum += solidAngle(vertices[t[0]] - q, vertices[t[1]] - q, vertices[t[2]] - q);
      }
    } else {
      stack[top++] = n.first + 1;
      stack[top++] = n.first;
    }
  }
  return sum / (4.0 * M_PI);
}

}  // namespace unidist::mesh
