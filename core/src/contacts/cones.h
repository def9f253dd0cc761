// Direction cones for the normal cone search (algorithms.md §1.2): grow by a vector, merge two, and the
// intersection test, with a slack angle so that the leaf tests' tolerances are never pruned away. Internal.
#pragma once

#include "mesh/bvh.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace unidist::contact {

using DirCone = mesh::NormalCone;

constexpr double kPi = 3.14159265358979323846;

/// Angle between unit vectors, accurate near 0 and π (atan2 of |cross| and dot).
inline double angleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

/// a rotated toward b (unit, not parallel to a unless the angle is 0) by `by` radians.
inline Eigen::Vector3d rotateToward(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double by) {
  Eigen::Vector3d side = b - a.dot(b) * a;  // the part of b orthogonal to a
  const double s = side.norm();
  if (!(s > 1e-300)) return a;
  side /= s;
  return (std::cos(by) * a + std::sin(by) * side).normalized();
}

/// Smallest enlargement of c that holds unit vector v (incremental, order-dependent, conservative).
inline void grow(DirCone& c, const Eigen::Vector3d& v) {
  if (c.halfAngle >= kPi) return;
  const double phi = angleBetween(c.axis, v);
  if (phi <= c.halfAngle) return;
  if (phi >= kPi - 1e-12) {  // opposite directions: no unique plane to rotate in
    c.halfAngle = kPi;
    return;
  }
  const double half = 0.5 * (c.halfAngle + phi);
  c.axis = rotateToward(c.axis, v, half - c.halfAngle);
  c.halfAngle = half;
}

/// A cone holding both.
inline DirCone merge(const DirCone& a, const DirCone& b) {
  if (a.halfAngle >= kPi || b.halfAngle >= kPi) return {a.axis, kPi};
  const double phi = angleBetween(a.axis, b.axis);
  if (phi + b.halfAngle <= a.halfAngle) return a;
  if (phi + a.halfAngle <= b.halfAngle) return b;
  const double half = 0.5 * (phi + a.halfAngle + b.halfAngle);
  if (half >= kPi || phi >= kPi - 1e-12) return {a.axis, kPi};
  return {rotateToward(a.axis, b.axis, half - a.halfAngle), half};
}

inline DirCone negated(const DirCone& c) { return {-c.axis, c.halfAngle}; }

/// Whether some direction lies in both cones (within `slack` radians). A cone of half-angle π/2 or more counts as
/// every direction: a normal set spanned by normals in so wide a cap may leave the cap (the cap is not convex).
inline bool intersects(const DirCone& a, const DirCone& b, double slack) {
  if (a.halfAngle >= 0.5 * kPi || b.halfAngle >= 0.5 * kPi) return true;
  return angleBetween(a.axis, b.axis) <= a.halfAngle + b.halfAngle + slack;
}

}  // namespace unidist::contact
