// A tight lower bound on the distance from a point to a rational Bézier patch, from the Bernstein form of the
// squared distance: with X(s,t) the homogeneous numerator and W(s,t) the weight, |S − q|² = |X − q·W|² / W²,
// both products of two degree-(n, m) Bernstein polynomials, so degree (2n, 2m) with coefficients A_kl and
// W_kl (W_kl > 0 for positive weights). On [0,1]² a ratio of two such polynomials is at least the smallest
// ratio of their coefficients: |S − q|² >= min A_kl / W_kl. Unlike a bounding ball it is exact where the
// distance is constant — the centre of a rational sphere, where every subpatch ties and balls never prune.
// Internal.
#pragma once

#include "unidist/nurbs.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace unidist::nurbs {

/// Buffers of bernsteinDistanceBound, kept by its caller across the nodes of one query (no allocation per node).
struct BernsteinScratch {
  std::vector<double> A, W, binomialU, binomialV;
  std::vector<Eigen::Vector3d> a;
};

/// C(n, k) for k = 0..n into `out`.
inline void binomialRow(int n, std::vector<double>& out) {
  out.assign(static_cast<std::size_t>(n + 1), 1.0);
  for (int k = 1; k <= n; ++k) out[static_cast<std::size_t>(k)] = out[static_cast<std::size_t>(k - 1)] * (n - k + 1) / k;
}

/// Proved: |S(s,t) − q| >= this on the whole patch (rounding allowance included).
inline double bernsteinDistanceBound(const RationalBezierPatch& patch, const Eigen::Vector3d& q, BernsteinScratch& w) {
  const int n = patch.degreeU, m = patch.degreeV;
  const std::size_t cols = static_cast<std::size_t>(2 * m + 1);
  w.A.assign(static_cast<std::size_t>(2 * n + 1) * cols, 0.0);
  w.W.assign(w.A.size(), 0.0);
  w.a.resize(patch.net.size());
  binomialRow(n, w.binomialU);
  binomialRow(m, w.binomialV);
  double magnitude = 0;
  for (std::size_t k = 0; k < patch.net.size(); ++k) {
    w.a[k] = patch.net[k].head<3>() - q * patch.net[k][3];
    magnitude = std::max(magnitude, w.a[k].norm() / patch.net[k][3]);
  }
  const auto index = [m](int i, int j) { return static_cast<std::size_t>(i * (m + 1) + j); };
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= m; ++j) {
      const double cij = w.binomialU[static_cast<std::size_t>(i)] * w.binomialV[static_cast<std::size_t>(j)];
      for (int i2 = 0; i2 <= n; ++i2)
        for (int j2 = 0; j2 <= m; ++j2) {
          const double c = cij * w.binomialU[static_cast<std::size_t>(i2)] * w.binomialV[static_cast<std::size_t>(j2)];
          const std::size_t kl = static_cast<std::size_t>(i + i2) * cols + static_cast<std::size_t>(j + j2);
          w.A[kl] += c * w.a[index(i, j)].dot(w.a[index(i2, j2)]);
          w.W[kl] += c * patch.net[index(i, j)][3] * patch.net[index(i2, j2)][3];
        }
    }
  // The common factor 1 / (C(2n,k)·C(2m,l)) cancels in each ratio.
  double least = std::numeric_limits<double>::infinity();
  for (std::size_t kl = 0; kl < w.A.size(); ++kl) {
    if (!(w.W[kl] > 0)) return 0;  // not a positive-weight patch: no bound
    least = std::min(least, w.A[kl] / w.W[kl]);
  }
  // Each coefficient is a sum of (n+1)²(m+1)² products, each exact to a few ulps of magnitude².
  const double rounding = 8.0 * (n + 1) * (m + 1) * std::numeric_limits<double>::epsilon() * magnitude;
  return std::max(0.0, std::sqrt(std::max(0.0, least)) - rounding - 1e-15 * q.cwiseAbs().maxCoeff());
}

}  // namespace unidist::nurbs
