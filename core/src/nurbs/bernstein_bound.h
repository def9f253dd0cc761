// A tight lower bound on the distance from a point to a rational Bézier patch, from the Bernstein form of the
// squared distance: with X(s,t) the homogeneous numerator and W(s,t) the weight, |S − q|² = |X − q·W|² / W²,
// both products of two degree-(n, m) Bernstein polynomials, so degree (2n, 2m) with coefficients A_kl and
// W_kl (W_kl > 0 for positive weights). On [0,1]² a ratio of two such polynomials is at least the smallest
// ratio of their coefficients: |S − q|² >= min A_kl / W_kl. Unlike a bounding ball it is exact where the
// distance is constant — the centre of a rational sphere, where every subpatch ties and balls never prune.
// Internal.
#pragma once

#include "nurbs/bernstein_product.h"
#include "nurbs/binomial.h"
#include "unidist/nurbs.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace unidist::nurbs {

/// Buffers of bernsteinDistanceBound, kept by its caller across the nodes of one query (no allocation per node).
struct BernsteinScratch {
  std::vector<double> A, W;
  std::vector<Eigen::Vector3d> y;
};

/// |X − q·W|² (into A) and W² (into W) in Bernstein form of degree (2n, 2m), coefficient (k, l) at k·(2m + 1) + l:
/// products of the patch's degree-(n, m) forms, each coefficient a mean of products of control points (the
/// weights C(n,i)·C(n,k−i) / C(2n,k) sum to one over i, likewise in m). The sums are taken on binomial-scaled
/// points and scaled back once per coefficient (the same terms, so the same rounding order of magnitude).
/// y (net.size() entries) receives X_ij − q·W_ij. Coeffs: anything with assign(size, value) and operator[].
template <class Coeffs>
void squaredDistanceForm(const RationalBezierPatch& patch, const Eigen::Vector3d& q, Eigen::Vector3d* y, Coeffs& A,
                         Coeffs& W) {
  const int n = patch.degreeU, m = patch.degreeV;
  const int cols = 2 * m + 1;
  A.assign(static_cast<std::size_t>((2 * n + 1) * cols), 0.0);
  W.assign(static_cast<std::size_t>((2 * n + 1) * cols), 0.0);
  const int count = (n + 1) * (m + 1);
  // Scaled copies on the stack up to a bicubic net (the common case, asked per node of every query).
  constexpr int kLocal = 16;
  std::array<Eigen::Vector3d, kLocal> yLocal;
  std::array<double, kLocal> wLocal;
  std::vector<Eigen::Vector3d> yHeap(count > kLocal ? static_cast<std::size_t>(count) : 0);
  std::vector<double> wHeap(yHeap.size());
  Eigen::Vector3d* ys = yHeap.empty() ? yLocal.data() : yHeap.data();
  double* ws = wHeap.empty() ? wLocal.data() : wHeap.data();
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= m; ++j) {
      const int k = i * (m + 1) + j;
      const Eigen::Vector4d& P = patch.net[static_cast<std::size_t>(k)];
      const double scale = binomial(n, i) * binomial(m, j);
      y[k] = P.head<3>() - q * P[3];
      ys[k] = scale * y[k];
      ws[k] = scale * P[3];
    }
  addScaledSquare(n, m, ys, 1.0, &A[0]);
  addScaledSquare(n, m, ws, 1.0, &W[0]);
  unscaleByBinomials(2 * n, 2 * m, &A[0]);
  unscaleByBinomials(2 * n, 2 * m, &W[0]);
}

/// bernsteinDistanceBound's allowance for rounding, on a patch of `terms` control points within `magnitude` of
/// q: each coefficient is a mean of up to `terms` products, each exact to a few ulps of magnitude².
inline double bernsteinRounding(std::size_t terms, double magnitude, const Eigen::Vector3d& q) {
  return 8.0 * static_cast<double>(terms) * std::numeric_limits<double>::epsilon() * magnitude +
         1e-15 * q.cwiseAbs().maxCoeff();
}

/// Proved: |S(s,t) − q| >= this on the whole patch (rounding allowance included).
inline double bernsteinDistanceBound(const RationalBezierPatch& patch, const Eigen::Vector3d& q, BernsteinScratch& w) {
  w.y.resize(patch.net.size());
  squaredDistanceForm(patch, q, w.y.data(), w.A, w.W);
  double magnitude = 0;
  for (std::size_t k = 0; k < patch.net.size(); ++k) magnitude = std::max(magnitude, w.y[k].norm() / patch.net[k][3]);
  double least = std::numeric_limits<double>::infinity();
  for (std::size_t kl = 0; kl < w.A.size(); ++kl) {
    if (!(w.W[kl] > 0)) return 0;  // not a positive-weight patch: no bound
    least = std::min(least, w.A[kl] / w.W[kl]);
  }
  return std::max(0.0, std::sqrt(std::max(0.0, least)) - bernsteinRounding(patch.net.size(), magnitude, q));
}

}  // namespace unidist::nurbs
