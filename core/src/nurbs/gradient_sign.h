// A proof that a piece of a rational Bézier patch holds no local minimum of the search's objective over the
// patch (patch corners aside: they are evaluated anyway). Each gradient component is a polynomial numerator
// over a power of the positive weight W, so its sign is the numerator's; Bernstein coefficients all of one
// sign prove it nowhere zero on the closed piece. A minimum inside the patch needs both components zero, one
// on a patch edge needs the component along the edge zero and the other not pointing into the patch. The search
// asks this of a small flat piece before a Newton run: a proved piece needs none, and one that fails and that
// its run leaves (the run found another basin) is split, since it may hold a basin of its own. Internal.
//
// For |S − q|: ∂/∂s ½|S − q|² = (S − q)·S_s = Y·D_s / W³ with Y = X − q W and D_s = X_s W − X W_s (X the
// homogeneous numerator). With X' = X − c W about the piece's centre c and q' = q − c, Y·D_s = X'·D_s − q'·(W D_s):
// both products are independent of q, so each piece keeps their Bernstein coefficients (made once, on first
// need) and a query combines them in a few flops per coefficient. For −d·S the numerator is −d·D_s, whose
// sign is that of −d·(W D_s).
#pragma once

#include "nurbs/patch_tree.h"

#include <array>
#include <vector>

namespace unidist::nurbs {

/// The q-independent parts of a piece's gradient numerators, as Bernstein coefficients (u-major): for ∂/∂s of
/// degree (3n − 1, 3m), for ∂/∂t of degree (3n, 3m − 1).
struct GradientForm {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  int su = 0, tu = 0, sv = 0, tv = 0;  // degrees (s, t) of the ∂/∂s and ∂/∂t grids
  std::vector<double> pu, pv;            // X'·D
  std::array<std::vector<double>, 3> qu, qv;  // W D, coordinate by coordinate (a query's loop is vectorised)
  // Every |coefficient| is at most sizeP (X'·D) or sizeQ (W D); errP and errQ bound their distance from the
  // exact subpatch's (the net's rounding and this computation's).
  double sizeP = 0, sizeQ = 0, errP = 0, errQ = 0;
  double speedS = 0, speedT = 0;  // bounds on |S_s| and |S_t| over the piece (its own parameters)
  // Per net edge (s = 0, s = 1, t = 0, t = 1): the largest distance of its control points from its first one,
  // so that a collapsed edge (a pole) is recognised without touching the net per query.
  double edgeSpread[4] = {0, 0, 0, 0};
};

/// The point of a patch edge collapsed to within `negligible` (a pole) that the node touches, or null.
const Eigen::Vector3d* collapsedCorner(const PatchNode& n, const PatchForest& forest, double negligible);

/// The node's form, made on first call (once per node, thread-safe); a cached node's form is counted in the
/// forest's bytes.
const GradientForm& gradientForm(const PatchNode& n, const PatchForest& forest);

/// Buffers of the proofs, kept by the caller across the nodes of one query.
struct GradientScratch {
  std::vector<double> u, v;
};

/// Proved: no point of the node is a local minimum of |S − q| over the node's patch, except patch corners and
/// points of a patch edge collapsed to within `negligible` (a pole: there every point is within it of a corner);
/// with `reach`, for every q within that distance of the given one.
bool pointHoldsNoMinimum(const PatchNode& n, const PatchForest& forest, const Eigen::Vector3d& q, GradientScratch& g,
                         double negligible, double reach = 0);
/// Signs of the gradient of ½|S − q|² over a node: +1 or −1 where every coefficient of the numerator has that
/// sign beyond its rounding, else 0.
struct PointGradientSigns {
  int whole[2] = {0, 0};         // ∂/∂s and ∂/∂t throughout the node
  int along[4] = {0, 0, 0, 0};   // the component along each side of the node (s = s0, s = s1, t = t0, t = t1) on it
};
PointGradientSigns pointGradientSigns(const PatchNode& n, const PatchForest& forest, const Eigen::Vector3d& q,
                                      GradientScratch& g);
/// The same for −d·S (d a unit vector).
bool supportHoldsNoMinimum(const PatchNode& n, const PatchForest& forest, const Eigen::Vector3d& d, GradientScratch& g,
                           double negligible);

}  // namespace unidist::nurbs
