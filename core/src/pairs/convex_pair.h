// Two convex solids by GJK/EPA on their support maps (convex/gjk.h): the route of every pair of convex
// primitives and convex meshes, and of the overlaps of NURBS solids proved convex. Internal.
#pragma once

#include "convex/gjk.h"
#include "pairs/pair_query.h"

namespace unidist::detail {

/// The contract's answer from GJK/EPA's, its bounds widened to hold the value.
DistanceResult fromConvex(const ConvexDistance& c, const char* method);

/// a and b convex solids (support() their support maps). Certified only when the bounds meet within the
/// tolerance and GJK/EPA converged.
DistanceResult convexPair(const PosedModel& a, const PosedModel& b, const QueryContext& ctx);

}  // namespace unidist::detail
