// A lower bound on the translational penetration depth from all the contacts of a round solid at once. A ball
// (c, ρ) inside one solid K holds points p_i of the other solid's surface: each stays inside the moved ball, so
// inside K, until K moves by t with |t − (p_i − c)| >= ρ, and the solids part only when every p_i has left. The
// depth is then at least the distance from 0 to the outside of the union of the balls (p_i − c, ρ). Where the
// contacts surround the way out (a ball sunk in a ring's hole, touching all round and leaving up the axis) that
// is the depth itself, deeper than any one point is inside (Kim et al.'s Minkowski sums, of balls here).
// Internal.
#pragma once

#include "pairs/pair_query.h"

#include <Eigen/Core>

#include <vector>

namespace unidist::detail {

/// The least |t| with |t − v_i| >= radius for every i: the distance from the origin to the outside of the union
/// of the balls (v_i, radius) that hold the origin (the others are ignored), less its rounding; 0 for none.
/// Exact (to rounding) from the nearest points of the spheres, of their pairwise circles and their triple points
/// that no other ball covers; at least the deepest ball's own radius − |v_i|.
double outsideBallUnion(const std::vector<Eigen::Vector3d>& centres, double radius);

/// The bound above for B moving against A, with the ball about each solid's bounding-sphere centre that its
/// point query proves inside it, and the other model's surface points inside that ball nearest its centre and
/// nearest where `escape` (a translation of B that separates them, or zero) takes it (NURBS: per patch, from a
/// grid of starts; other models give none yet). 0 where no ball holds a surface point of the other.
double ballUnionBound(const PosedModel& a, const PosedModel& b, const Eigen::Vector3d& escape);

}  // namespace unidist::detail
