// GJK between the convex hulls of two small point sets (subpatch control nets), B's points in B's own frame:
// its supports map the direction into that frame and only the chosen point out of it, so no per-pair copy of
// the net is made. For the pair searches' lower bounds, which only need to know whether a pair is apart by more
// than a threshold. Internal.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <limits>
#include <vector>

namespace unidist::nurbs {

struct HullDistance {
  double lower = 0;  // proved: the hulls are at least this far apart (negative or −inf: they may overlap)
  Eigen::Vector3d pointA = Eigen::Vector3d::Zero(), pointB = Eigen::Vector3d::Zero();  // closest hull points (A's frame)
  int iterations = 0;
};

/// a: A's points; b: B's points, mapped into A's frame by X_AB. startA, startB: a point of each hull (A's frame)
/// to begin from (the supports along a direction from A toward B are a good start). Ends when the bounds meet to
/// `tolerance`, or once `lower` reaches stopAbove (then the points are not the closest).
HullDistance hullDistance(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b,
                          const Eigen::Isometry3d& X_AB, const Eigen::Vector3d& startA, const Eigen::Vector3d& startB,
                          double tolerance, int maxIterations,
                          double stopAbove = std::numeric_limits<double>::infinity());

}  // namespace unidist::nurbs
