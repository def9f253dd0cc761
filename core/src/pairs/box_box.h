// Signed distance between two solid boxes (internal).
#pragma once

#include "convex/gjk.h"

#include <Eigen/Geometry>

#include <limits>

namespace unidist::detail {

/// One of the 15 candidate separating axes of two boxes, in A's frame.
struct BoxAxis {
  enum class Kind { FaceOfA, FaceOfB, EdgePair };
  Kind kind = Kind::FaceOfA;
  int i = 0;  ///< FaceOfA: A's axis; EdgePair: the direction axis of A's edge
  int j = 0;  ///< FaceOfB: B's axis; EdgePair: the direction axis of B's edge
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  ///< unit, pointing from A toward B
  /// Overlap of the two boxes' projections on it: > 0 overlapping, < 0 minus the gap between them.
  double overlap = std::numeric_limits<double>::infinity();
};

struct BoxAxes {
  /// The smallest overlap over all 15 axes (face axes win ties): the penetration depth when the boxes overlap,
  /// minus the largest axis gap when they are apart.
  BoxAxis smallest;
  BoxAxis smallestFace;  ///< the same over the six face axes only
};

/// Separating-axis test of box A (half extents halfA, centred at the origin of its frame) and box B (halfB) whose
/// axes are the columns of R_AB and whose centre is p_AB, both in A's frame.
BoxAxes boxSeparatingAxes(const Eigen::Vector3d& halfA, const Eigen::Vector3d& halfB, const Eigen::Matrix3d& R_AB,
                          const Eigen::Vector3d& p_AB);

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
