// Certified extreme values over a rational Bézier patch, exact to rounding where the patch curves away from the
// level set through the extreme point.
// * The support value along n: max over the patch of n·S(s,t). With S = X / W (W > 0), n·S <= c wherever
//   h_c = n·X − c·W <= 0; when h_c's Hessian is negative semidefinite over the whole patch (checked on the
//   Bernstein coefficients of its second derivatives) h_c is concave, so at any point x0
//   h_c <= h_c(x0) + ∇h_c(x0)·(y − x0) and the linear part is largest at a corner. Taking x0 the maximiser of
//   n·S over the patch (projected Newton) and c its value, that bound is c to rounding: the exact support, where
//   the control points' support exceeds it by the net's bulge (second order in the patch size).
// * The farthest and nearest distance from a point c: the same with h_γ = ±|X − c·W|² − γ·W², of degree
//   (2p, 2q): the farthest where the patch lies inside a sphere about c that touches it, the nearest where it
//   lies outside one. Internal.
#pragma once

#include "unidist/nurbs.h"

#include <limits>

namespace unidist::nurbs {

struct SupportBound {
  bool proved = false;
  double upper = 0;  // when proved: n·S(s,t) <= upper over the whole patch (rounding allowance included)
};

/// n need not be unit; the patch and n in one frame.
SupportBound certifySupport(const RationalBezierPatch& patch, const Eigen::Vector3d& n);

/// The greatest value over the unit square of a polynomial in tensor-product Bernstein form (degrees p, q,
/// coefficients u-major), proved where it is concave about its maximiser (then exact to rounding), not proved
/// elsewhere. `error`: how far each coefficient may be off, per unit of the largest.
SupportBound certifyPolynomialMaximum(int p, int q, const double* coefficients, double error);

/// Halvings of a distance form before its bound is taken as it stands (certifyDistanceExtreme's default).
constexpr int kDistanceHalvings = 256;

struct DistanceExtreme {
  bool proved = false;
  double value = 0;  // when proved: |S − c| <= value (farthest) or >= value (nearest) over the whole patch
};

/// The greatest (farthest = true) or least distance from c to the patch, both in one frame: exact to rounding
/// where proved by concavity, else the bound of the Bernstein coefficients' ratios (second order in the patch
/// size); without `exact` only the latter. With `enough` (a distance that would do: farthest at most, or nearest
/// at least, this), a bound short of it is sharpened by subdividing the form (ratio_subdivision.h), at most
/// `halvings` times. Not proved
/// only for non-finite input or non-positive weights.
DistanceExtreme certifyDistanceExtreme(const RationalBezierPatch& patch, const Eigen::Vector3d& c, bool farthest,
                                       bool exact = true, double enough = std::numeric_limits<double>::quiet_NaN(),
                                       int halvings = kDistanceHalvings);

}  // namespace unidist::nurbs
