// A certified support value of a rational Bézier patch along a direction n: max over the patch of n·S(s,t),
// proved to rounding where the patch curves away from the plane n·x = c on its far side. With S = X / W
// (W > 0), n·S <= c wherever h_c = n·X − c·W <= 0; when h_c's Hessian is negative semidefinite over the whole
// patch (checked on the Bernstein coefficients of its second derivatives) h_c is concave, so at any point x0
// h_c <= h_c(x0) + ∇h_c(x0)·(y − x0) and the linear part is largest at a corner. Taking x0 the maximiser of
// n·S over the patch (projected Newton) and c its value, that bound is c to rounding: the exact support, where
// the control points' support exceeds it by the net's bulge (second order in the patch size). Internal.
#pragma once

#include "unidist/nurbs.h"

namespace unidist::nurbs {

struct SupportBound {
  bool proved = false;
  double upper = 0;  // when proved: n·S(s,t) <= upper over the whole patch (rounding allowance included)
};

/// n need not be unit; the patch and n in one frame.
SupportBound certifySupport(const RationalBezierPatch& patch, const Eigen::Vector3d& n);

}  // namespace unidist::nurbs
