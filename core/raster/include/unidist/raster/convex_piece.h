// A convex piece of a decomposition, built from the corners and faces a file gives, with the promise checked:
// the hull replaces the piece only when the piece is convex (otherwise the union would silently be a different
// solid).
#pragma once

#include "unidist/raster/convex_union.h"

#include <string>

namespace unidist::raster {

/// How far (relative to the piece's bounding-box diagonal) a corner or face centre may lie inside the hull and
/// still count as on it: room for coordinates written with six or seven digits.
inline constexpr double kConvexityAllowance = 1e-6;

/// The hull of `vertices` after checking that every vertex and every face centre lies on it. Throws InputError
/// naming `name` for a non-convex piece (and whatever convexHull throws: too few points, flat, NaN).
ConvexPolytope convexPiece(const std::vector<Eigen::Vector3d>& vertices, const std::vector<std::array<int, 3>>& faces,
                           const std::string& name);

}  // namespace unidist::raster
