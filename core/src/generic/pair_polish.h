// The last step of a separation answer that involves a NURBS model: alternating local projections from its
// closest points (Newton on the NURBS surfaces, exact projections on everything else), kept only while the
// realised gap shrinks. The search stops where its bounds meet the tolerance, anywhere in the bracket; the
// polish takes the pair on to its local minimum, so the answer's true error no longer depends on where the
// search stopped (a tighter tolerance never answers less accurately: docs/dial.md). Internal.
#pragma once

#include "pairs/pair_query.h"

namespace unidist::detail {

/// Improves a separated answer (r.lowerBound > 0) in place: points, distance, normal, upper bound. The bounds stay
/// proved (every pair it keeps is a pair of realised surface points); the status is settled against `tolerance`.
void polishSeparation(const PosedModel& a, const PosedModel& b, DistanceResult& r, double tolerance);

/// polishSeparation for every pair, two NURBS solids included: the NURBS–NURBS routine's own call, where its best
/// pair lies on a patch edge (a Newton run clamped there; the local minimum may lie across the seam).
/// enough: a step shrinking the gap by less ends the polish (0: only rounding does).
void polishAcrossPatches(const PosedModel& a, const PosedModel& b, DistanceResult& r, double tolerance,
                         double enough = 0);

}  // namespace unidist::detail
