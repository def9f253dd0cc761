// Closest points between a point and a segment, and between two segments (internal).
//
// Segment–segment follows the structure of Ericson, "Real-Time Collision Detection" §5.1.9 (the minimum of a
// convex quadratic over the unit square is either its unconstrained minimiser, when that lies inside, or on one
// of the four sides), but solves the interior case by Gram–Schmidt against the longer segment instead of the
// normal equations: the normal equations lose sin²(angle) to cancellation, so for segments 1e-8 rad from
// parallel they would place the closest points anywhere along the overlap and over-estimate the distance by up
// to ~1e-8 × length. Here the distance is accurate to a few ulps of the coordinates at every angle; only the
// parameters (s, t) are ill-conditioned near parallel, as they must be (the crossing point itself is).
// Zero-length segments and exactly parallel segments are handled (the side cases cover them).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products

namespace unidist::detail {

struct PointSegmentClosest {
  double t = 0;                                    ///< parameter in [0, 1]: closest = a + t (b − a)
  Eigen::Vector3d point = Eigen::Vector3d::Zero(); ///< closest point of the segment
  double distance = 0;                             ///< |p − point|
};

/// Closest point of segment [a, b] to p. A zero-length segment gives t = 0.
PointSegmentClosest closestPointSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b);

struct SegmentSegmentClosest {
  double s = 0, t = 0;                          ///< parameters in [0, 1] on [p1, q1] and [p2, q2]
  Eigen::Vector3d point1 = Eigen::Vector3d::Zero();  ///< p1 + s (q1 − p1)
  Eigen::Vector3d point2 = Eigen::Vector3d::Zero();  ///< p2 + t (q2 − p2)
  double distance = 0;                          ///< |point1 − point2|
};

/// Closest points of segments [p1, q1] and [p2, q2]. Where they are not unique (parallel overlapping
/// segments) one of the minimising pairs is returned, deterministically.
SegmentSegmentClosest closestSegmentSegment(const Eigen::Vector3d& p1, const Eigen::Vector3d& q1,
                                            const Eigen::Vector3d& p2, const Eigen::Vector3d& q2);

}  // namespace unidist::detail
