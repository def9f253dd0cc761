// Generic searches that need nothing but point queries and surface cells, so they serve every pair of
// representations: alternating projection (Johnson & Cohen 2004) to find good pairs fast, and a best-first
// branch and bound over one model's surface cells to prove how far from optimal they are. Internal.
#pragma once

#include "pairs/pair_query.h"

#include <vector>

namespace unidist::detail {

/// A pair of world points, one on each surface, from alternating projection.
struct PointPair {
  Eigen::Vector3d onA, onB;
  double gap = 0;  ///< |onB − onA|
  int iterations = 0;
};

/// Alternating closest-point queries from a start point (world): p_A = A(start), p_B = B(p_A), p_A = A(p_B), ...
/// Stops when the gap shrinks by less than tolerance, on a 2-cycle, or after maxSteps.
PointPair alternate(const PosedModel& a, const PosedModel& b, const Eigen::Vector3d& start_W, double tolerance,
                    int maxSteps);

/// Start points for alternating projection: the closest points of the two world bounding boxes, the bounding
/// spheres' centres and the samples of both models' root surface cells.
std::vector<Eigen::Vector3d> alternationStarts(const PosedModel& a, const PosedModel& b);

/// The distance field of a model at a world point: its signed distance when it is a solid, else the unsigned
/// distance (a model without an inside has no sign). 1-Lipschitz either way.
double fieldValue(const PosedModel& field, const Eigen::Vector3d& p_W);

/// Result of minimising the other model's distance field over one model's surface.
struct SurfaceMinimum {
  double value = std::numeric_limits<double>::infinity();  ///< best field value found (an upper bound on the min)
  Eigen::Vector3d point = Eigen::Vector3d::Zero();         ///< world point of the surface where it was found
  double lowerBound = -std::numeric_limits<double>::infinity();  ///< proved: min >= lowerBound
  int evaluations = 0;
  bool exhausted = false;  ///< the budget ran out before the bounds met
};

/// min over points p of `surface`'s surface of the field of `field` at p: its signed distance when it is a
/// solid, else its unsigned distance. Cells are pruned by field(centre) − radius (the field is 1-Lipschitz).
/// `upperHint`, with `hintPoint`, is a known value (e.g. from alternation) that starts the pruning.
/// `budgetOnceNegative` caps the evaluations spent after the first negative value (an overlap of two solids,
/// where the deepest point only seeds the depth search and a flat deepest region would exhaust any budget).
SurfaceMinimum minimizeFieldOverSurface(const PosedModel& surface, const PosedModel& field, double upperHint,
                                        const Eigen::Vector3d& hintPoint, double tolerance, int budget,
                                        int budgetOnceNegative = std::numeric_limits<int>::max());

}  // namespace unidist::detail
