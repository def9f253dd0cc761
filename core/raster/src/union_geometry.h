// The CPU side of the union queries (internal): input checks, the proofs that a point is inside a piece or
// outside every piece, and the exact exit of a ray from the union. Everything the rendering suggests is
// checked here in double precision before it is reported.
#pragma once

#include "unidist/raster/convex_union.h"
#include "unidist/types.h"

#include <vector>

namespace unidist::raster::detail {

/// Throws InputError unless every piece is a well-formed polytope (as convexHull makes them). `what` names the
/// union in the message ("union", "union A", ...).
void validateUnion(const ConvexUnion& pieces, const char* what);

/// A facet of a piece, and where a proof may push off it.
struct FacetRef {
  int piece = -1, facet = -1;
};

class UnionGeometry {
 public:
  /// `origin` only sets the size of the rounding margins (the query point); pieces must be valid.
  UnionGeometry(const ConvexUnion& pieces, const Eigen::Vector3d& origin);

  const ConvexUnion& pieces() const { return pieces_; }
  const Aabb& box(int piece) const { return boxes_[static_cast<std::size_t>(piece)]; }
  /// Plane values within ±margin of 0 are undecided (rounding of n·p + d, qhull's outer planes).
  double margin() const { return margin_; }
  /// The step off a facet that proves a point is on the boundary (≫ margin, ≪ any size that matters).
  double pushOut() const { return pushOut_; }

  /// max over the piece's facets of n·p + d: < 0 inside, its negation is the depth when inside.
  double planeMax(int piece, const Eigen::Vector3d& p) const;
  /// p is inside no piece, each by more than the margin.
  bool provedOutsideAll(const Eigen::Vector3d& p) const;
  /// p lies in the piece up to the margin.
  bool inPiece(int piece, const Eigen::Vector3d& p) const { return planeMax(piece, p) <= margin_; }

  /// The first point where the ray O + t·u (u unit, O inside the union) leaves the union, walked exactly over
  /// every piece's interval: `t` such that O + (t + pushOut)·u is proved outside, and the facet it leaves by.
  struct Exit {
    double t = 0;
    FacetRef facet;
    bool proved = false;  ///< O + (t + pushOut)·u was proved outside every piece
  };
  Exit walkRay(const Eigen::Vector3d& O, const Eigen::Vector3d& u) const;

  /// x is on the boundary up to pushOut: in `piece` (up to the margin) and x + pushOut·w outside every piece for
  /// one of the unit directions w given.
  bool provedOnBoundary(const Eigen::Vector3d& x, int piece, const std::vector<Eigen::Vector3d>& pushDirections) const;

 private:
  const ConvexUnion& pieces_;
  std::vector<Aabb> boxes_;
  double margin_ = 0, pushOut_ = 0;
};

}  // namespace unidist::raster::detail
