// Global translational penetration depth of two overlapping solids of any representation, with proved
// bounds (algorithms.md §5.2, "certified bracket" and "ray version", done without a convex decomposition).
// Internal.
//
// Work in translation space: U = {t : A and B moved by t have intersecting interiors}; the depth is the
// distance from the origin to the boundary of U, i.e. min over directions e of the first exit of the ray t = s·e.
//  * Upper bound: any t whose translated pair the pair's own routine proves interior-disjoint. Along a
//    direction, an exponential search then bisection finds such a t near the ray's exit; it is polished by
//    re-aiming along the contact normal found there (the boundary's normal in translation space), which is
//    exact in one step where the boundary is a face and converges where it is curved.
//  * Lower bound: an overlap witness. A point x inside A at depth dA and inside B moved by t at depth dB
//    proves that every translation within min(dA, dB) of t still overlaps (both depths are 1-Lipschitz), so
//    a ball of t-space lies in U. Marching along the axis of a cone of directions with these balls proves a
//    first exit no smaller than the march reached for every ray of the cone. Cones are the cells of a cube
//    map, refined best-first on the smallest proved exit. The deepest point of one surface inside the other
//    solid (the search before this one) is a second proved lower bound.
// The answer is certified when the bounds meet within the tolerance, bounded otherwise, within a budget of
// witness evaluations derived from maxIterations.
#pragma once

#include "pairs/pair_query.h"

#include <optional>

namespace unidist::detail {

/// What the caller already knows about the overlap.
struct OverlapSeed {
  double provedDepth = 0;  ///< a proved lower bound on the depth (e.g. the deepest surface point's depth), >= 0
  /// The depth of the point behind provedDepth as its point query realised it (provedDepth is that less the
  /// query's error bound, which near a surface grows as the squared distance's rounding over the distance).
  double realisedDepth = 0;
  Eigen::Vector3d deepPoint = Eigen::Vector3d::Zero();  ///< a world point inside both solids, or near both
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  ///< a promising escape direction for B (unit)
  double knownEscape = std::numeric_limits<double>::infinity();  ///< a proved escape distance (upper bound)
  Eigen::Vector3d knownEscapeDirection = Eigen::Vector3d::UnitZ();
};

/// How much of the search translationalDepth runs.
enum class DepthScope {
  Full,        ///< the escapes, then the cone search until the bounds meet or the budget ends
  SeedEscape,  ///< only the escape from the seed's direction: certified when it meets seed.provedDepth
};

/// a and b are solids whose interiors are known to overlap. Returns the contract's answer: distance = −depth,
/// normal = the direction B moves to separate, pointA on A and pointB on B with pointB − pointA = distance·normal.
DistanceResult translationalDepth(const PosedModel& a, const PosedModel& b, const QueryContext& ctx,
                                  const OverlapSeed& seed, DepthScope scope = DepthScope::Full);

}  // namespace unidist::detail

namespace unidist::detail {

/// A seed for translationalDepth from short searches of each surface against the other solid's field (the
/// deepest points found), and supporting-plane escapes along the axes and the deepest point's normal.
OverlapSeed seedOverlap(const PosedModel& a, const PosedModel& b, const QueryContext& ctx);

/// Raises seed.provedDepth by polishing the deepest surface points near seed.deepPoint: projected descent of
/// the other solid's signed distance over each surface (its gradient is that solid's outward normal). Every
/// value is realised (a surface point that deep in the other solid must travel that far to get out), so the
/// result stays a proved lower bound; sampled surface searches are first order and stop short of it.
void deepenSeed(const PosedModel& a, const PosedModel& b, double tolerance, OverlapSeed& seed);

/// A seed from a point where the two surfaces meet or cross (within the tolerance): each surface's deepest point
/// inside the other solid by the same local descent as deepenSeed, started just inside the other solid (along
/// its inward normal at the contact, further out until a start lies inside), and the supporting-plane escapes.
/// Local: provedDepth is realised (proved), but it is the global deepest point's only where one lens overlaps.
OverlapSeed seedFromContact(const PosedModel& a, const PosedModel& b, const Eigen::Vector3d& contact_W,
                            double tolerance);

/// Solids that meet at contact_W (their surfaces within the tolerance there): the depth certified by the escape
/// along the normal at the deepest point near the contact alone (seedFromContact; DepthScope::SeedEscape), as in
/// a shallow overlap, where the escape meets the realised depth; empty when it does not (several overlapping
/// lenses, a deep non-convex overlap), and the caller runs the full search.
std::optional<DistanceResult> shallowDepth(const PosedModel& a, const PosedModel& b, const QueryContext& ctx,
                                           const Eigen::Vector3d& contact_W);

/// Lowers seed.knownEscape by supporting-plane escapes along the world's and both models' axes and seed.direction.
void addPlaneEscapes(const PosedModel& a, const PosedModel& b, OverlapSeed& seed);

}  // namespace unidist::detail
