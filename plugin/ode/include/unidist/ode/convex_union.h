// Opt-in: solids given as unions of convex pieces (a convex decomposition) as unidist geoms whose contacts with each
// other come from the image-space penetration depth of unidist::raster (docs/raster.md): one contact per pair at
// the minimum translation that separates the two unions, where ODE's own colliders (and the ordinary unidist
// geom) would see several unrelated per-piece depths. Against any other geom such a geom is the pieces' hull
// triangles as one triangle mesh. Available when unidist was built with the raster target (libosmesa6-dev,
// libqhull-dev). One off-screen context for the whole plugin, created on the first image-space query, serialises
// those queries.
#pragma once

#include <Eigen/Core>
#include <ode/ode.h>

#include <vector>

namespace unidist::ode {

/// A unidist geom (init() first) for the union of the convex hulls of `pieces` (one point set per piece, in the
/// geom's frame); `resolution` = pixels per cube-face side (8..4096), the accuracy of the depth. Throws InputError
/// for an empty list, a degenerate piece (flat, fewer than 4 points, NaN) or a resolution out of range.
dGeomID createConvexUnionGeom(dSpaceID space, const std::vector<std::vector<Eigen::Vector3d>>& pieces,
                              int resolution = 128);

}  // namespace unidist::ode
