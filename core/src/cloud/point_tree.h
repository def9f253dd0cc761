// The hierarchy over a point cloud's points: the same flat AABB tree as the mesh's (mesh/bvh.h, leaves of at
// most 4 points) plus a ball per node for the surface cells. Internal.
#pragma once

#include "mesh/bvh.h"

#include <vector>

namespace unidist::cloud {

struct PointTree {
  mesh::Bvh tree;
  mesh::BigVector<BoundingSphere> spheres;  ///< per node: centred at the box centre, holding every point below
  mesh::BigVector<std::array<std::uint32_t, 2>> ranges;  ///< per node: slots [begin, end)
  std::size_t memoryBytes() const;
};

PointTree buildPointTree(const std::vector<Eigen::Vector3d>& points);

/// Index of the point nearest to q (the first met on exact ties) and its squared distance.
std::uint32_t nearestPoint(const PointTree& tree, const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& q,
                           double& squaredDistance);

}  // namespace unidist::cloud
