#include "unidist/raster/convex_piece.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace unidist::raster {
namespace {

/// Depth of p inside the hull: min over facets of −(n·p + d) (≤ 0 on or outside the boundary).
double depthInside(const ConvexPolytope& hull, const Eigen::Vector3d& p) {
  double depth = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector4d& plane : hull.planes) depth = std::min(depth, -(plane.head<3>().dot(p) + plane[3]));
  return depth;
}

}  // namespace

ConvexPolytope convexPiece(const std::vector<Eigen::Vector3d>& vertices, const std::vector<std::array<int, 3>>& faces,
                           const std::string& name) {
  const std::string label = name.empty() ? std::string("a convex piece") : "convex piece '" + name + "'";
  ConvexPolytope hull;
  try {
    hull = convexHull(vertices);
  } catch (const InputError& e) {
    throw InputError(label + ": " + e.what());
  }
  Aabb box;
  for (const Eigen::Vector3d& v : vertices) box.extend(v);
  const double allowance = kConvexityAllowance * box.diagonal();
  for (const Eigen::Vector3d& v : vertices)
    if (depthInside(hull, v) > allowance)
      throw InputError(label + " is not convex: a corner lies " + std::to_string(depthInside(hull, v)) +
                       " inside its hull (split it into convex pieces, one OBJ group each)");
  for (const std::array<int, 3>& f : faces) {
    for (int i : f)
      if (i < 0 || i >= static_cast<int>(vertices.size()))
        throw InputError(label + ": face index " + std::to_string(i) + " out of range");
    const Eigen::Vector3d centre = (vertices[f[0]] + vertices[f[1]] + vertices[f[2]]) / 3;
    if (depthInside(hull, centre) > allowance)
      throw InputError(label + " is not convex: a face passes " + std::to_string(depthInside(hull, centre)) +
                       " inside its hull (split it into convex pieces, one OBJ group each)");
  }
  return hull;
}

}  // namespace unidist::raster
