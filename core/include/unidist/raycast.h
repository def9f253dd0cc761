// Ray casting against any model: the first point where a ray meets the model's surface, found by sphere tracing
// on the model's unsigned distance (|closestPoint(q).signedDistance|): no surface lies within that distance of
// q, so stepping by it never jumps over the surface. Works for every representation through the point query
// alone (primitives, meshes, NURBS, point clouds).
//
// Rules:
//  * A hit is the first ray point within `tolerance` of the surface; t is refined by Newton steps on the signed
//    distance for solids so that transversal hits are accurate well below the tolerance.
//  * A ray starting inside a solid reports where it leaves (as ODE's own ray colliders do for spheres and
//    boxes): the first surface point along the ray, startedInside = true.
//  * `normal` is the surface normal facing the ray origin (normal · dir <= 0): the outward normal for a hit
//    from outside, the inward one when leaving a solid; −dir for a point cloud (a point has no normal).
//  * Point clouds: a hit when the ray passes within `tolerance` of a point (feature = the point's index).
//  * Termination: the ray is first clipped to the model's bounds grown by the tolerance; every step is at least
//    the tolerance and at most kMaxRaySteps steps are taken. When the cap is reached (a very long grazing run
//    along a surface) the answer is "no hit" and `exhausted` is set.
#pragma once

#include "unidist/model.h"

namespace unidist {

constexpr int kMaxRaySteps = 200000;

struct RayHit {
  bool hit = false;
  double t = 0;  ///< distance from the origin along the (unit) direction
  Eigen::Vector3d point = Eigen::Vector3d::Zero();   ///< world
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< world, unit, facing the ray origin
  int feature = 0;                                    ///< the model's feature at the hit (triangle, point, ...)
  bool startedInside = false;                         ///< the origin was inside a solid: this is the exit point
  bool exhausted = false;                             ///< the step cap was reached (reported as no hit)
};

/// First hit of the ray origin_W + t·dir_W, 0 <= t <= maxLength, with model m posed at X_WM. dir_W must be unit
/// (within 1e-6), maxLength >= 0 and finite, tolerance > 0 and finite; otherwise InputError.
RayHit raycast(const Model& m, const Eigen::Isometry3d& X_WM, const Eigen::Vector3d& origin_W,
               const Eigen::Vector3d& dir_W, double maxLength, double tolerance);

}  // namespace unidist
