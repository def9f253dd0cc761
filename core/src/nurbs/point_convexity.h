// A proof that a piece of a patch holds no point nearer to q than a Newton end inside it (rounding aside):
// f = ½|S − q|² is convex over the piece — its Hessian H_ab = S_a·S_b + (S − q)·S_ab positive definite
// throughout — so f lies above its tangent plane at the Newton end, and above f(end) − |g|²/(2 λ) with λ the
// least curvature. Where it holds, the search closes the piece and all below it at once, and the
// one-minimum premise of its leaves is not needed there. Internal.
//
// With S = X / W, D_a = X_a W − X W_a (so S_a = D_a / W²) and E_ab = (D_a)_b W − 2 W_b D_a (S_ab = E_ab / W³):
// W⁴ H_ab = D_a·D_b + (X − q W)·E_ab, a polynomial. About the piece's centre c (X' = X − c W, r = q − c) it is
// P_ab − r·Q_ab with P_ab = D_a·D_b + X'·E_ab and Q_ab = W E_ab, both independent of q: each piece keeps their
// Bernstein coefficients (made once, on first need), and a query combines them in a few flops per coefficient.
// Coefficients bound the polynomial on the piece, so their least values bound the Hessian's entries.
#pragma once

#include "nurbs/gradient_sign.h"
#include "nurbs/patch_search.h"

#include <array>
#include <vector>

namespace unidist::nurbs {

/// P_ab and Q_ab (coordinate by coordinate) for ab = ss, st, tt over a node, in its own local parameters.
struct CurvatureForm {
  bool valid = false;  // false: degree too high for the form to pay, or a coefficient not finite
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double weight4 = 0;  // the largest W⁴ on the node (its largest control weight to the fourth)
  std::array<std::vector<double>, 3> p;
  std::array<std::array<std::vector<double>, 3>, 3> q;
  // Every |coefficient| is at most sizeP (P) or sizeQ (|Q|); errP and errQ bound their distance from the exact
  // subpatch's (the net's rounding and this computation's).
  std::array<double, 3> sizeP{}, sizeQ{}, errP{}, errQ{};
  // The values at the node's middle and the coefficients' largest distance from them (a quick first test).
  std::array<double, 3> middleP{}, spreadP{}, spreadQ{};
  std::array<Eigen::Vector3d, 3> middleQ{};
};

/// The Hessian of ½|S − q|² is positive definite at the node's middle (evaluated, a few hundred flops): where it
/// is not, the form cannot prove convexity, so callers ask this first and spare the node its form.
bool convexAtMiddle(const PatchNode& n, const Eigen::Vector3d& q);

/// The node's form, made on first call (once per node, thread-safe; counted in the forest's bytes when cached).
const CurvatureForm& curvatureForm(const PatchNode& n, const PatchForest& forest);

/// A proved lower bound on the least eigenvalue of the Hessian of ½|S − q|² over the node (its local
/// parameters): positive where the function is proved convex there, else zero. A quick test first (the values
/// at the node's middle and the coefficients' spread about them), then every coefficient. With `reach`, the
/// bound holds for every point within that distance of q.
double leastCurvature(const CurvatureForm& form, const Eigen::Vector3d& q, double reach = 0);

/// Proved: |S − q| >= this over the node, given leastCurvature(form, q) = curvature > 0 and h a point of the
/// node's patch inside the node's box with its gradient (a Newton run's end).
double convexDistanceBound(const PatchNode& n, const Eigen::Vector3d& q, const PatchHit& h, double curvature);

/// Proved: |S − q| >= this over the node, where h (a Newton run's end, with its gradient) lies on a patch edge
/// the node touches: the gradient points out of the patch across that edge throughout the node, so the node's
/// least distance is on the edge, and there it is convex along the edge (at a patch corner: both components
/// point out, and h is the node's nearest point). Minus infinity where this is not proved. The search closes
/// with it the pieces whose nearest point lies on the patch boundary, where the distance is seldom convex over
/// the whole piece.
double edgeDistanceBound(const PatchNode& n, const PatchForest& forest, const Eigen::Vector3d& q, const PatchHit& h,
                         GradientScratch& g);

}  // namespace unidist::nurbs
