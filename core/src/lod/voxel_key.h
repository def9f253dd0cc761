// Integer cells of a uniform grid, for welding and decimation. Internal.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace unidist::lod {

using VoxelKey = std::array<std::int64_t, 3>;

/// The cell of side `side` holding p, counted from `origin` (callers keep (p − origin)/side well inside int64).
inline VoxelKey voxelOf(const Eigen::Vector3d& p, const Eigen::Vector3d& origin, double side) {
  const Eigen::Vector3d g = (p - origin) / side;
  return {static_cast<std::int64_t>(std::floor(g.x())), static_cast<std::int64_t>(std::floor(g.y())),
          static_cast<std::int64_t>(std::floor(g.z()))};
}

struct VoxelKeyHash {
  std::size_t operator()(const VoxelKey& k) const {
    return static_cast<std::size_t>(k[0] * 73856093 ^ k[1] * 19349663 ^ k[2] * 83492791);
  }
};

}  // namespace unidist::lod
