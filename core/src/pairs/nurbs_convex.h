// A solid NURBS model against a convex solid (box, capsule, cylinder, cone, sphere, convex mesh): best-first
// descent of the NURBS patch trees, each subpatch bounded below by GJK between the convex hull of its control
// points (which holds the subpatch: positive weights) and the solid. That bound is second order in the
// subpatch size, so a near-touching pair is decided in a few levels, where the generic surface search (first
// order) needs ~1/tolerance cells. Upper bounds are realised surface points measured by the solid's exact
// signed distance. Overlaps (a surface point inside the solid, or one solid holding the other) go to the
// global translation-depth search, whose separation tests come back here. Internal.
#pragma once

#include "pairs/pair_query.h"

namespace unidist::detail {

/// a is a solid NurbsModel, b a convex solid.
DistanceResult nurbsConvex(const PosedModel& a, const PosedModel& b, const QueryContext& ctx);

}  // namespace unidist::detail
