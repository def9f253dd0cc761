// Global separation distance between triangle meshes and point clouds: a best-first traversal (min-heap on
// the lower bound) of the two bounding volume hierarchies with upper/lower-bound pruning, exact
// triangle–triangle, triangle–point and point–point distances at the leaves. Lower bound per node pair: the
// larger of the ball–ball gap and the gap between A's box and B's box turned into A's frame; for two meshes
// also the gap between the nodes' rectangle swept spheres (mesh/rss.h), computed only when a pair is taken up
// with the cheap bounds below the best. The search goes straight into the nearer child pair when no queued
// pair is nearer, and past 512 queued pairs goes depth first below the best-first front (see traverse()). At
// the leaves, every triangle pair gets a lower bound (boxes' gap, gaps along the centroids' line and along
// both normals) and the pairs below the best are measured exactly, nearest bound first. Overlapping
// solids (and a model without an inside reaching into a solid) go to the generic routine, which handles
// penetration. Stops when every pair left has a lower bound within half the tolerance (less rounding slack)
// of the best distance: certified, bounds [lower, upper] proved; when the leaf-pair budget
// (16 × maxIterations) runs out first, bounded. Measured: best-first visits far fewer leaf pairs than a
// nearer-first depth-first search (env/rob: 17–21 µs against 0.5–1.2 ms for the depth-first variant on the
// same poses); the RSS bound, the dive and the depth-first overflow took the linked tori from 3.7–5.8× FCL's
// time to about half of it, and keeping the dive best first took env/rob to a third of FCL's time or less
// (docs/meshes.md).
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
