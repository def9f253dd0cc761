// The CPU polish of an image-space closest boundary point (internal): a descent over the facets near the best
// point — the foot of O on each facet plane, and on each crease (two facets' line, clipped to both pieces and
// with every other piece's stretch removed, so its ends are the corners) — each kept only when proved to lie
// on the union's boundary.
#pragma once

#include "union_geometry.h"

namespace unidist::raster::detail {

/// The best proved boundary point so far.
struct BestPoint {
  double distance = 0;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  FacetRef facet;
  bool proved = false;
};

/// Facets whose planes pass within `radius` of x, on pieces that come within `radius` of x, nearest first (at
/// most `limit`).
std::vector<FacetRef> facetsNear(const UnionGeometry& g, const Eigen::Vector3d& x, double radius, std::size_t limit);

/// Rounds of: the best proved candidate over `facets`, then the facets within `radius` of the new best point;
/// until a round finds nothing closer. True when `best` improved.
bool polishBoundaryPoint(const UnionGeometry& g, const Eigen::Vector3d& O, std::vector<FacetRef> facets, double radius,
                         BestPoint& best);

}  // namespace unidist::raster::detail
