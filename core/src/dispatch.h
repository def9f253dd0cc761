// The only place that knows which pairs of representations have a special routine. Internal.
#pragma once

#include "pairs/pair_query.h"

namespace unidist::detail {

/// Answers the pair with its special routine when it has one (the reversed pair is derived here, once),
/// with GJK/EPA when both models are convex, and with the generic routine otherwise.
DistanceResult dispatchPair(const PosedModel& a, const PosedModel& b, const QueryContext& ctx);

/// Name of the routine dispatchPair would use (for docs and tests).
const char* routineName(ModelType a, ModelType b);

}  // namespace unidist::detail
