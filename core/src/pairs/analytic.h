// Pairs answered in closed form, and bounds every pair routine can use. Internal.
#pragma once

#include "pairs/pair_query.h"

#include <optional>

namespace unidist::detail {

/// Half-space A against any model B (solid or not): exact, via B's support map (its lowest point).
DistanceResult planeAny(const PosedModel& plane, const PosedModel& other, const QueryContext& ctx);
/// Sphere A against a convex solid B: exact, one point query at the centre. Also exact for any solid B
/// when the answer is a separation (returns false in `exact` otherwise).
DistanceResult sphereAny(const PosedModel& sphere, const PosedModel& other, const QueryContext& ctx, bool& exact);

/// A sphere sunk into a solid that is not convex (`sunk`: sphereAny's answer): certified when the sphere moved out
/// along the contact normal by the centre's depth (and a quarter tolerance) is proved clear of the solid by one
/// point query; none where that way is blocked (a ball in a ring's hole) or the surface curves round the ball.
std::optional<DistanceResult> sphereEscapeAlongNormal(const PosedModel& sphere, const PosedModel& other,
                                                      const QueryContext& ctx, const DistanceResult& sunk);
/// Capsule–capsule: segment–segment distance minus both radii; exact (also when penetrating: the
/// Minkowski difference of two capsules is a convex set grown by a ball).
DistanceResult capsuleCapsule(const PosedModel& a, const PosedModel& b, const QueryContext& ctx);

/// Proved lower bound on the signed distance from one direction u (unit, A toward B): the gap between the
/// convex hulls' supporting planes, min_B u·b − max_A u·a (negative: an overlap along u, which bounds the
/// penetration depth because translating B by that much along u separates the hulls).
double supportGapLowerBound(const PosedModel& a, const PosedModel& b, const Eigen::Vector3d& u);

/// Rounding slack for bounds computed from coordinates of magnitude `scale`.
double roundingSlack(double scale);

/// Sets lower/upper bounds to value ± rounding slack and status certified (for closed-form answers).
void markExact(DistanceResult& r, double scale);

}  // namespace unidist::detail
