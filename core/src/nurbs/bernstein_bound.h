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

/// C(n, k) for n <= 62 (degrees are at most 31).
inline double binomial(int n, int k) {
  double c = 1;
  for (int i = 1; i <= k; ++i) c = c * (n - k + i) / i;
  return c;
}

/// Proved: |S(s,t) − q| >= this on the whole patch (rounding allowance included).
inline double bernsteinDistanceBound(const RationalBezierPatch& patch, const Eigen::Vector3d& q) {
  const int n = patch.degreeU, m = patch.degreeV;
  const int rows = 2 * n + 1, cols = 2 * m + 1;
  std::vector<double> A(static_cast<std::size_t>(rows * cols), 0.0), W(A.size(), 0.0);
  std::vector<Eigen::Vector3d> a(patch.net.size());
  double magnitude = 0;
  for (std::size_t k = 0; k < patch.net.size(); ++k) {
    a[k] = patch.net[k].head<3>() - q * patch.net[k][3];
    magnitude = std::max(magnitude, a[k].norm() / patch.net[k][3]);
  }
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= m; ++j) {
      const double cij = binomial(n, i) * binomial(m, j);
      const std::size_t ij = static_cast<std::size_t>(i * (m + 1) + j);
      for (int i2 = 0; i2 <= n; ++i2)
        for (int j2 = 0; j2 <= m; ++j2) {
          const std::size_t ij2 = static_cast<std::size_t>(i2 * (m + 1) + j2);
          const double c = cij * binomial(n, i2) * binomial(m, j2);
          const std::size_t kl = static_cast<std::size_t>((i + i2) * cols + (j + j2));
          A[kl] += c * a[ij].dot(a[ij2]);
          W[kl] += c * patch.net[ij][3] * patch.net[ij2][3];
        }
    }
  // The common factor 1 / (C(2n,k)·C(2m,l)) cancels in each ratio.
  double least = std::numeric_limits<double>::infinity();
  for (std::size_t kl = 0; kl < A.size(); ++kl) {
    if (!(W[kl] > 0)) return 0;  // not a positive-weight patch: no bound
    least = std::min(least, A[kl] / W[kl]);
  }
  // Each coefficient is a sum of (n+1)²(m+1)² products, each exact to a few ulps of magnitude².
  const double rounding = 8.0 * (n + 1) * (m + 1) * std::numeric_limits<double>::epsilon() * magnitude;
  return std::max(0.0, std::sqrt(std::max(0.0, least)) - rounding - 1e-15 * q.cwiseAbs().maxCoeff());
}

}  // namespace unidist::nurbs
