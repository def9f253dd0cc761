// Two solid NURBS models: best-first search over pairs of patch-tree nodes, each pair bounded below by GJK
// between the convex hulls of the two subpatches' control points (each hull holds its subpatch: positive
// weights). The bound is second order in the node size, so a smooth point contact is proved in ~log(1/tol)
// levels with a handful of pairs per level, where the generic surface branch and bound (first order) needs
// ~1/tolerance cells. Upper bounds are realised: GJK's hull witnesses projected onto their surfaces. Only a
// proved separation is answered here; surfaces that meet, containment or an exhausted budget go to the
// generic routine (and so to the translation-depth search). Internal.
#pragma once

#include "pairs/pair_query.h"

namespace unidist::detail {

/// a and b are solid NurbsModels.
DistanceResult nurbsNurbs(const PosedModel& a, const PosedModel& b, const QueryContext& ctx);

}  // namespace unidist::detail
