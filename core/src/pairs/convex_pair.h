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

/// The same on given world-frame support maps (a NURBS solid proved convex answers by a local ascent,
/// nurbs/convex_support.h, where its model's support() is a global search).
DistanceResult convexPairOfSupports(const SupportFn& supportA, const SupportFn& supportB, const QueryContext& ctx);

/// A convex solid: a model that says so (isConvex(): primitives, convex meshes), or a NURBS solid proved convex
/// (its support map being a search, NurbsModel keeps isConvex() false).
bool convexSolid(const Model& m);

/// The world-frame support map of a posed model: NurbsModel's proved convex ones by nurbs::convexSupport.
SupportFn supportMapOf(const PosedModel& m);

}  // namespace unidist::detail
