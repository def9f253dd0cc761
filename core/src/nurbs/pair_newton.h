// Newton on the extremal-distance equations of two rational Bézier patches: minimise ½|S_A(s,t) − X·S_B(u,v)|²
// over [0,1]⁴ (box-constrained, active set at the bounds, Levenberg damping where the Hessian is not positive
// definite, a step is accepted only when the distance decreases). Its end points are realised surface points,
// so every value it returns is a proved upper bound of the distance. Internal.
#pragma once

#include "unidist/nurbs.h"

namespace unidist::nurbs {

struct PairHit {
  Eigen::Vector4d x = Eigen::Vector4d::Zero();  // (s, t) on A's patch, (u, v) on B's patch
  Eigen::Vector3d pA = Eigen::Vector3d::Zero(), pB = Eigen::Vector3d::Zero();  // A's frame
  double value = 0;                                                              // |pB − pA|
  int evaluations = 0;
};

/// X_AB maps B's patch into A's frame. Starts at x0 (clamped to the box).
PairHit polishPair(const RationalBezierPatch& a, const RationalBezierPatch& b, const Eigen::Isometry3d& X_AB,
                   const Eigen::Vector4d& x0);

}  // namespace unidist::nurbs
