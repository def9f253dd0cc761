#include "lod/decimate.h"

#include "lod/voxel_key.h"

#include <cmath>
#include <unordered_map>

namespace unidist::lod {

Built decimate(const PointCloud& cloud, double maxDeviation) {
  const Aabb box = cloud.localBounds();
  const double side = maxDeviation / std::sqrt(3.0) * (1 - 1e-12);  // the cell diagonal stays below the level
  // Cells are counted in 64-bit integers: a side this small against the extent drops nothing anyway.
  if (!(side > 0) || !((box.max - box.min).maxCoeff() / side < 1e15)) return {};
  std::unordered_map<VoxelKey, std::size_t, VoxelKeyHash> firstInCell;
  const std::vector<Eigen::Vector3d>& points = cloud.points();
  const bool withNormals = !cloud.normals().empty();
  std::vector<Eigen::Vector3d> kept, keptNormals;
  double deviation = 0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const auto [it, isNew] = firstInCell.emplace(voxelOf(points[k], box.min, side), kept.size());
    if (isNew) {
      kept.push_back(points[k]);
      if (withNormals) keptNormals.push_back(cloud.normals()[k]);
    } else {
      deviation = std::max(deviation, (points[k] - kept[it->second]).norm());
    }
  }
  if (kept.size() == points.size()) return {};
  Built b;
  b.model = std::make_unique<PointCloud>(std::move(kept), std::move(keptNormals));
  b.deviation = deviation;
  return b;
}

}  // namespace unidist::lod
