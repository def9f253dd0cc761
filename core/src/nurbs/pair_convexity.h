// A local convexity certificate for two rational Bézier patches: proves f = ½|S_A(s,t) − X·S_B(u,v)|² convex
// over a box of (s, t, u, v) — its Hessian positive definite throughout, by the mean-value form around a point x
// of the box: H(y) ∈ H(x) ± Σ_c max|∂_c H|·|y_c − x_c|, with ∂_c H enclosed through interval bounds of the
// surfaces' derivatives up to order three (Bernstein coefficients of the homogeneous subpatch) — and then bounds
// f below on the box by its tangent plane at x. At a stationary point (Newton's end) that bound is the distance
// there, less rounding: every pair of nodes inside the box is settled at once, where the control-hull bounds
// (second order in the node size) would need nodes of size ~√tolerance. Internal.
#pragma once

#include "unidist/nurbs.h"

namespace unidist::nurbs {

struct ConvexityCertificate {
  bool proved = false;
  double lower = 0;  // when proved: |S_A − X·S_B| >= lower over the whole box (rounding allowance included)
  /// Certified margin: (enclosed variation of the Hessian) / (least eigenvalue of H(x)); proved when < 1, and
  /// roughly proportional to the box size (so a failed box says how much smaller one may succeed). Infinite
  /// when H(x) itself is not positive definite.
  double ratio = 0;
};

/// X_AB maps B's patch into A's frame; lo <= x <= hi componentwise, all in [0,1]⁴ (local patch parameters).
ConvexityCertificate certifyConvexPair(const RationalBezierPatch& a, const RationalBezierPatch& b,
                                       const Eigen::Isometry3d& X_AB, const Eigen::Vector4d& lo,
                                       const Eigen::Vector4d& hi, const Eigen::Vector4d& x);

}  // namespace unidist::nurbs
