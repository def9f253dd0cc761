// Two solid NURBS models: the bound-and-subdivide search of Thomas et al. over pairs of patch-tree nodes.
// Proved lower bounds (balls, then GJK between the convex hulls of the two subpatches' control points: positive
// weights keep each subpatch in its hull) and normal-cone tests (a pair holds an extremal pair only if some
// segment between them is normal to both surfaces, or orthogonal to a patch edge) prune; Newton on the
// extremal-distance equations realises the minimum, and a local convexity certificate around it settles the
// pairs next to it. Only a proved separation is answered here; surfaces that
// meet within the tolerance and containment go to the generic routine (and so to the translation-depth
// search); an exhausted budget answers with the bounds it proved (status bounded). Internal.
#pragma once

#include "pairs/pair_query.h"

namespace unidist::detail {

/// a and b are solid NurbsModels.
DistanceResult nurbsNurbs(const PosedModel& a, const PosedModel& b, const QueryContext& ctx);

}  // namespace unidist::detail
