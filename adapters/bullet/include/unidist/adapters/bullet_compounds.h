// A Bullet compound of convex children as a union of convex pieces: the input of the image-space penetration
// depth (unidist::raster) that the Bullet plugin can use for compound–compound pairs (unidist/bullet/
// raster_compounds.h). Each piece is the corner points of one child, in the compound's frame.
#pragma once

#include <Eigen/Core>

#include <vector>

class btCompoundShape;

namespace unidist::bullet {

struct CompoundPieces {
  std::vector<std::vector<Eigen::Vector3d>> pieces;  ///< one point set per convex child (its hull is the piece)
  /// Bullet's outside margin of the union: the smallest of the children's (btConvexHullShape: its margin,
  /// 0.04 by default; btBoxShape keeps its margin inside: 0). Exact when the children share one margin.
  double outerMargin = 0;
};

/// Children may be btConvexHullShape, btBoxShape or nested compounds of those (their transforms and Bullet's
/// local scaling applied). Throws InputError naming the first other child type, or an empty compound.
CompoundPieces convexPiecesOfCompound(const btCompoundShape& compound);

}  // namespace unidist::bullet
