// Convex hull of a point set as outward-oriented triangles (incremental construction; meant for the few hundred
// vertices of an ODE convex geom, O(n·faces)).
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <vector>

namespace unidist::odeadapt {

/// Triangles (indices into points) of the hull, oriented outward. Points within 1e-12 × the extent of a hull
/// face's plane count as on it (not added). Throws InputError when the points span no volume.
std::vector<std::array<std::uint32_t, 3>> convexHull(const std::vector<Eigen::Vector3d>& points);

}  // namespace unidist::odeadapt
