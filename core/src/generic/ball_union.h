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
/// of the balls (v_i, radius), less its rounding; 0 where none holds the origin.
/// Exact (to rounding) from the nearest points of the spheres, of their pairwise circles and their triple points
/// that no other ball covers; at least the deepest ball's own radius − |v_i|. `nearest` (when given) receives
/// the point of the outside found nearest the origin (zero when none was), and `away` a unit direction leaving
/// every sphere through it (the nearest point of their outward normals' hull to the origin, normalised; zero when
/// the hull holds the origin).
double outsideBallUnion(const std::vector<Eigen::Vector3d>& centres, double radius,
                        Eigen::Vector3d* nearest = nullptr, Eigen::Vector3d* away = nullptr);

/// The bound above for B moving against A, with the ball about each solid's bounding-sphere centre that its
/// point query proves inside it, and the other model's surface points inside that ball nearest its centre and
/// nearest where `escape` (a translation of B that separates them, or zero) takes it (NURBS: per patch, from a
/// grid of starts; other models give none yet). 0 where no ball holds a surface point of the other. Its end
/// point, the way out the contacts leave, is where the escape search looks next.
struct BallUnionBound {
  double depth = 0;                                ///< proved: the depth is at least this
  Eigen::Vector3d way = Eigen::Vector3d::Zero();   ///< the translation of B the bound ends at: the contacts let go
  Eigen::Vector3d away = Eigen::Vector3d::Zero();  ///< a unit direction off every contact there (zero: none)
};
BallUnionBound ballUnionBound(const PosedModel& a, const PosedModel& b, const Eigen::Vector3d& escape);

}  // namespace unidist::detail
