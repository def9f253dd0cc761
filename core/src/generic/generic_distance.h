// The generic pair routine: any two models, through point queries and surface cells only. Internal.
#pragma once

#include "pairs/pair_query.h"

namespace unidist::detail {

DistanceResult genericPair(const PosedModel& a, const PosedModel& b, const QueryContext& ctx);

}  // namespace unidist::detail
