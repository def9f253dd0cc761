// How far a pair of models has moved relative to each other: the guard test of the warm starts that keep
// contacts or minima between global searches (ContactCache in contacts/manifold.cpp, the Tracker in
// tracking/tracker.cpp). Internal.
#pragma once

#include "unidist/model.h"

#include <cmath>
#include <limits>

namespace unidist::contact {

/// The bounding-box diagonal, infinite for an unbounded model (a half-space).
inline double boundedDiagonal(const Model& m) {
  const Aabb box = m.localBounds();
  return box.bounded() ? box.diagonal() : std::numeric_limits<double>::infinity();
}

/// Largest displacement of any point of a ball between two poses: |ΔX·c| + ‖R1 − R0‖₂·r. For rotations
/// ‖R1 − R0‖₂ = 2 sin(angle/2) = ‖R1 − R0‖_F / √2: no angle to extract (asked for every pair every step), and no
/// cancellation at small angles.
inline double motionBound(const Eigen::Isometry3d& X0, const Eigen::Isometry3d& X1, const BoundingSphere& s) {
  return (X1 * s.center - X0 * s.center).norm() + (X1.linear() - X0.linear()).norm() * std::sqrt(0.5) * s.radius;
}

/// The motion between two relative poses X_AB, measured on the smaller model (a half-space's ball is infinite:
/// the other one is measured).
inline double relativeMotion(const Model& a, const Model& b, const Eigen::Isometry3d& X_AB0,
                             const Eigen::Isometry3d& X_AB1) {
  const BoundingSphere sa = a.localBoundingSphere(), sb = b.localBoundingSphere();
  if (sb.radius <= sa.radius) return motionBound(X_AB0, X_AB1, sb);  // B moving in A's frame
  return motionBound(X_AB0.inverse(), X_AB1.inverse(), sa);           // A moving in B's frame
}

}  // namespace unidist::contact
