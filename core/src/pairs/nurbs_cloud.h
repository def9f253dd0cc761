// A NURBS model against a point cloud: min over the cloud's points of their signed distance to the NURBS solid
// (unsigned for an open NURBS), on the two hierarchies (patch tree, cloud point tree). Each point's exact value
// is the NURBS point query with its error bound.
//  * Solid NURBS, inside first: cloud nodes whose ball a centre query proves clear of the surface lie wholly on
//    one side; nodes that may cross it are split down to their points. If any point is inside, the answer is
//    minus the greatest depth, found best-first on an upper bound of each inside node's depth (a surface point's
//    distance plus the node's radius).
//  * No point inside (or an open NURBS): best-first over (patch node, cloud node) pairs as in nurbs_mesh: balls,
//    the normal-cone test, GJK between the subpatch's control-point hull and the cloud node's box (a leaf: its
//    points); a cloud leaf met by a small enough patch node gets its points' queries, which settle it.
// An exhausted budget answers with the bounds it has (status bounded). A deepest point inside by no more than the
// point query's unsure margin (1e-9 × the NURBS size, where its sign is not reliable) goes to the generic
// routine. Internal.
#pragma once

#include "pairs/pair_query.h"

namespace unidist::detail {

/// a is a NurbsModel (solid or open), b a PointCloud.
DistanceResult nurbsCloud(const PosedModel& a, const PosedModel& b, const QueryContext& ctx);

}  // namespace unidist::detail
