// Solids given as unions of convex pieces (a convex decomposition), as files and specs describe them, before any
// hull is built: the input of the image-space penetration depth (unidist::raster, `unidist distance --pd raster`).
#pragma once

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace unidist {

/// One convex piece as written: its corner points and, where the source has them, its faces (indices into
/// vertices; empty when the piece is "the hull of these points"). Faces let the hull builder check that the
/// piece really is convex instead of silently replacing it with its hull.
struct PieceSource {
  std::string name;
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;
};

/// An OBJ file: one piece per group ('o' or 'g' statement; faces before any group form one more piece). Another
/// mesh file (STL, PLY with faces): the whole mesh as one piece. A `box:` spec: its eight corners. Anything else
/// (point clouds, NURBS, round primitives) throws InputError saying what a piece set accepts.
std::vector<PieceSource> loadConvexPieces(const std::string& specOrPath);

}  // namespace unidist
