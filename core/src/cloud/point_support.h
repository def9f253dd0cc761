// The support point of a finite point set (a cloud's points, a mesh's vertices): the hull's support map. Internal.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace unidist {

/// The first of `points` (non-empty) that maximises dir·p, by a linear scan.
inline const Eigen::Vector3d& supportOfPoints(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& dir) {
  std::size_t best = 0;
  double bestValue = dir.dot(points[0]);
  for (std::size_t i = 1; i < points.size(); ++i) {
    const double v = dir.dot(points[i]);
    if (v > bestValue) {
      bestValue = v;
      best = i;
    }
  }
  return points[best];
}

}  // namespace unidist
