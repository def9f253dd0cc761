// A NURBS model against a triangle mesh: best-first over pairs (patch-tree node, mesh BVH node), the same
// bound-and-subdivide as NURBS–NURBS with the mesh's hierarchy on the other side. Proved lower bounds: balls,
// then GJK between the subpatch's control-point hull and the mesh node's box (a leaf: each of its triangles);
// the NURBS side's normal-cone test drops pairs that cannot hold a closest pair; realised upper bounds from
// node corners and from Newton toward GJK's witness on the triangle. Only proved separations are answered
// here (surfaces apart, and no containment where a model has an inside); surfaces meeting within the
// tolerance, containment and an unresolved search go to the generic routine (and so to the translation-depth
// search, whose separation tests come back here and stay cheap). Internal.
#pragma once

#include "pairs/pair_query.h"

namespace unidist::detail {

/// a is a NurbsModel, b a TriangleMesh (solid or open, either).
DistanceResult nurbsMesh(const PosedModel& a, const PosedModel& b, const QueryContext& ctx);

}  // namespace unidist::detail
