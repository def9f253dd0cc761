#include "cloud/point_tree.h"

#include <cmath>
#include <limits>

namespace unidist::cloud {

std::size_t PointTree::memoryBytes() const {
  return tree.memoryBytes() + mesh::footprintBytes(spheres) + mesh::footprintBytes(ranges);
}

PointTree buildPointTree(const std::vector<Eigen::Vector3d>& points) {
  std::vector<mesh::BvhItem> items(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) items[i] = {points[i], points[i]};
  PointTree t;
  t.tree = mesh::buildBvh(items);
  t.ranges = mesh::nodeRanges(t.tree);
  t.spheres.resize(t.tree.nodes.size());
  for (std::size_t i = 0; i < t.tree.nodes.size(); ++i) {
    // A node of one point (or of equal points) has its box centre exactly there and radius 0.
    const Eigen::Vector3d c = t.tree.nodes[i].center();
    double farthest = 0;
    for (std::uint32_t s = t.ranges[i][0]; s < t.ranges[i][1]; ++s)
      farthest = std::max(farthest, (points[t.tree.order[s]] - c).squaredNorm());
    t.spheres[i] = {c, mesh::paddedRadius(std::sqrt(farthest))};
  }
  return t;
}

std::uint32_t nearestPoint(const PointTree& tree, const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& q,
                           double& squaredDistance) {
  squaredDistance = std::numeric_limits<double>::infinity();
  std::uint32_t best = 0;
  const std::uint32_t* order = tree.tree.order.data();
  mesh::nearestSearch(tree.tree, q, squaredDistance, [&](std::uint32_t first, std::uint32_t n, double& bound) {
    for (std::uint32_t s = first; s < first + n; ++s) {
      const double d = (points[order[s]] - q).squaredNorm();
      if (d < bound) {
        bound = d;
        best = order[s];
      }
    }
  });
  return best;
}

}  // namespace unidist::cloud
