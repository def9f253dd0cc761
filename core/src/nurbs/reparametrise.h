// Möbius reparametrisation of rational Bézier patches (unidist/nurbs.h, RationalBezierPatch::stretchU): the
// same surface with balanced weights. Multiplying weight i of a degree-n direction by c^i turns
// Σ B_i(s) w_i P_i / Σ B_i(s) w_i into the original traced at σ(s) = c·s / (1 − s + c·s): Bernstein's
// s^i (1 − s)^(n−i) c^i is (c s)^i (1 − s)^(n−i), and dividing by (1 − s + c s)^n gives B_i(σ). Internal.
#pragma once

#include "unidist/nurbs.h"

#include <cmath>

namespace unidist::nurbs {

/// σ(s) = c·s / (1 − s + c·s): where local s of a patch stretched by c is in the original parameter.
inline double mobius(double c, double s) { return c * s / (1 - s + c * s); }

/// The stretch of the piece [s0, s1] of a direction stretched by c, as a patch of its own: the map from the
/// piece's local parameter to the original is again a Möbius map, with factor D(s1) / D(s0), D(s) = 1 + (c−1)s.
inline double pieceStretch(double c, double s0, double s1) { return (1 + (c - 1) * s1) / (1 + (c - 1) * s0); }

/// Balances the corner weights of a patch by a stretch per direction (the geometric means of the weights at
/// the two ends of each direction made equal) and scales the net so that the corners' geometric mean is 1.
/// The Euclidean control points are unchanged; the surface is the same, reparametrised (stretchU, stretchV).
inline void balanceWeights(RationalBezierPatch& patch) {
  const int n = patch.degreeU, m = patch.degreeV;
  const double w00 = patch.at(0, 0)[3], w0m = patch.at(0, m)[3], wn0 = patch.at(n, 0)[3], wnm = patch.at(n, m)[3];
  // a^n·(wn0·wnm)^½ = (w00·w0m)^½ and b^m·(w0m·wnm)^½ = (w00·wn0)^½, in logarithms (weights span 1e±300).
  const double logA = n > 0 ? (std::log(w00) + std::log(w0m) - std::log(wn0) - std::log(wnm)) / (2.0 * n) : 0.0;
  const double logB = m > 0 ? (std::log(w00) + std::log(wn0) - std::log(w0m) - std::log(wnm)) / (2.0 * m) : 0.0;
  const double logScale = -0.25 * (std::log(w00) + std::log(w0m) + std::log(wn0) + std::log(wnm)) -
                          0.5 * (n * logA + m * logB);
  if (!std::isfinite(logA) || !std::isfinite(logB) || !std::isfinite(logScale)) return;  // leave it as it came
  if (std::abs(logA) < 1e-12 && std::abs(logB) < 1e-12 && std::abs(logScale) < 1e-12) return;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= m; ++j) patch.at(i, j) *= std::exp(logScale + i * logA + j * logB);
  patch.stretchU *= std::exp(logA);
  patch.stretchV *= std::exp(logB);
}

}  // namespace unidist::nurbs
