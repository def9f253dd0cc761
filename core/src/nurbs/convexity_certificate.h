// Proof that a closed NURBS solid bounds a convex body, so that its penetration depth against another convex
// solid is the minimum of a support function (GJK/EPA) instead of a search over translations. Internal.
//
// The conditions, each proved with Bernstein coefficient signs (subdivided where a sign is not yet decided):
//  * every patch curves away from its outward normal everywhere: the second fundamental form is negative
//    semidefinite. With the homogeneous net P(u, v) and C·X = det[P, P_u, P_v, X] (a 4-vector of
//    polynomials), C·P_uu = −w⁴ (S_u × S_v)·S_uu and likewise for uv and vv, so the forms L = σ C·P_uu,
//    N = σ C·P_vv (σ the model's orientation) and L N − M² are polynomials that must be >= 0;
//  * every edge that is not collapsed to a point meets exactly one other patch edge with the same control
//    polygon (either way round, weights in proportion) and folds there toward the inside: the neighbour's
//    inward cross-derivative Q_σ has σ C·Q_σ >= 0 along the edge (a convex crease, or 0 on a smooth seam);
//  * the patches joined by those edges are one connected surface.
// A closed, connected, locally convex set is convex (Tietze–Nakajima); the conditions give local convexity at
// every boundary point — at a pole (an edge collapsed to a point) from its punctured neighbourhood, and at a
// vertex from its convex creases. Signs are proved up to rounding: a coefficient counts as >= 0 down to
// −1e-11 times the magnitude of the products it sums (a concavity that slight moves the surface by about
// that relative amount, far below any tolerance a query can ask for).
#pragma once

#include "unidist/nurbs.h"

#include <string>
#include <vector>

namespace unidist::nurbs {

struct ConvexityVerdict {
  bool proved = false;
  std::string reason;  ///< what failed, when not proved (names the patch and condition)
};

/// orientation: +1 when S_u × S_v points outward, −1 when inward (NurbsModel::orientation()). size: the model's
/// size, for matching edges (1e-9 × size). Patches of degree above kMaxCertifiedDegree are not certified.
ConvexityVerdict certifyConvexSolid(const std::vector<RationalBezierPatch>& patches, int orientation, double size);

constexpr int kMaxCertifiedDegree = 10;  // the form L N − M² has degree 8n − 4: within the binomial table

}  // namespace unidist::nurbs
