// Global separation distance between triangle meshes and point clouds: a quick descent (nearer child pair
// down to one leaf pair) for a first upper bound, then a best-first traversal (min-heap on the lower bound)
// of the two bounding volume hierarchies with upper/lower-bound pruning (lower bound per node pair:
// the larger of the ball–ball gap and the gap between A's box and B's box turned into A's frame), exact
// triangle–triangle, triangle–point and point–point distances at the leaves. Overlapping solids (and a
// model without an inside reaching into a solid) go to the generic routine, which handles penetration.
// Stops when the smallest lower bound left is within half the tolerance (less rounding slack) of the best
// distance: certified, bounds [lower, upper] proved; when the leaf-pair budget (16 × maxIterations) runs out
// first, bounded. Measured: best-first visits far fewer leaf pairs than a nearer-first depth-first search
// (env/rob: 17–21 µs against 0.5–1.2 ms for the depth-first variant on the same poses).
// Internal.
#pragma once

#include "pairs/pair_query.h"

namespace unidist::detail {

/// a and b are TriangleMesh models. `overlapFn` answers overlapping solids (default: the generic routine;
/// the dispatcher passes GJK/EPA for two convex meshes).
DistanceResult meshMesh(const PosedModel& a, const PosedModel& b, const QueryContext& ctx, PairFn overlapFn = nullptr);
/// a is a TriangleMesh, b a PointCloud.
DistanceResult meshCloud(const PosedModel& a, const PosedModel& b, const QueryContext& ctx);
/// a and b are PointCloud models.
DistanceResult cloudCloud(const PosedModel& a, const PosedModel& b, const QueryContext& ctx);

}  // namespace unidist::detail
