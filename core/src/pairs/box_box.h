// Signed distance between two solid boxes (internal).
#pragma once

#include "convex/gjk.h"

#include <Eigen/Geometry>

namespace unidist::detail {

/// Signed distance between box A (half extents halfA > 0, centred at the origin of frame A) at pose X_WA and box B
/// likewise, with the meaning of ConvexDistance (world frame). tolerance: absolute; <= 0 means as exact as double
/// allows.
///  * Overlapping or touching: exact. The minimum translation distance of two convex polyhedra is attained along a
///    face normal of their Minkowski difference, and for boxes those are the 15 separating-axis directions (3 + 3
///    face normals and the 9 edge–edge cross products), so the smallest overlap over them is the depth itself.
///    Witness points: B is moved by depth·normal to the touching configuration and the contact point is found
///    there by GJK. lowerBound = upperBound = distance (up to rounding).
///  * Apart: GJK on the two boxes' support maps (finite and exact on polytopes up to rounding), lower bound also
///    from the largest separating-axis gap.
/// Everything is computed in A's frame, so the answer's rounding follows the boxes' sizes and their distance,
/// not their distance from the world origin.
ConvexDistance boxBox(const Eigen::Vector3d& halfA, const Eigen::Isometry3d& X_WA, const Eigen::Vector3d& halfB,
                      const Eigen::Isometry3d& X_WB, double tolerance);

}  // namespace unidist::detail
