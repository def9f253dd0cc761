// Torus against a solid: the torus is its centre circle swept by a ball of the tube radius, so every
// question becomes a minimum over the circle's angle (see generic/circle_search.h). Internal.
#pragma once

#include "pairs/pair_query.h"

namespace unidist::detail {

/// Torus A against any solid B. Separation: certified by branch and bound over the angle. Penetration: the
/// deepest ball of the sweep gives a proved bound; an escape translation verified by the same search gives
/// the other; certified when they meet (locally convex contact), bounded otherwise.
DistanceResult torusSolid(const PosedModel& torus, const PosedModel& other, const QueryContext& ctx);

}  // namespace unidist::detail
