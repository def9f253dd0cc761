// A triangle mesh against a convex solid (box, capsule, cylinder, cone, sphere, convex mesh): best-first
// descent of the mesh's hierarchy, each node bounded below by the convex solid's signed distance at the
// node's ball centre minus the ball's radius (the signed distance is 1-Lipschitz), each triangle measured
// exactly against the solid by GJK (both are convex). Exact on flat contacts (a box face resting on a mesh
// face), where a search by point samples can never close its bounds. When the surfaces meet or one solid
// holds the other, the overlap goes to `convexOverlap` for a convex mesh (GJK/EPA), to the global depth
// search for a non-convex solid mesh, and to the generic routine for an open mesh (whose answer is its
// deepest point, not a translation). Internal.
#pragma once

#include "pairs/pair_query.h"

namespace unidist::detail {

/// a is a TriangleMesh, b a convex solid.
DistanceResult meshConvex(const PosedModel& a, const PosedModel& b, const QueryContext& ctx, PairFn convexOverlap);

}  // namespace unidist::detail
