// The support map of a NURBS solid proved convex (convexity_certificate.h), for GJK/EPA: a local ascent instead of
// the global search of NurbsModel::support. On the boundary of a convex body the sets {x : d·x >= h} are connected
// caps, so a strict local maximum of d·x inside a patch is the global one. Internal.
#pragma once

#include "unidist/nurbs.h"

#include <optional>

namespace unidist::nurbs {

/// The support point of `model` (proved convex) in direction d (model frame, any length > 0): the highest patch
/// corner when it tops every control point (highestCornerIfTop), else a Levenberg–Newton ascent of d·S on the
/// three patches with the highest control points, each from its best one's Greville parameters. Where every
/// ascent ends on a patch edge or without a negative definite Hessian of d·S (a pole, a seam, a flat face), the
/// model's global search answers instead.
Eigen::Vector3d convexSupport(const NurbsModel& model, const Eigen::Vector3d& d);

/// For any model (its forest's roots hold the patches' Euclidean control points): the patch corner as high along d
/// as the highest control point (to rounding), if one is. The surface lies in the control points' hull, so that
/// corner is then a support point exactly.
std::optional<Eigen::Vector3d> highestCornerIfTop(const PatchForest& forest, const Eigen::Vector3d& d);

}  // namespace unidist::nurbs
