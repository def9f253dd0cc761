// A tight lower bound on the distance from a point to a rational Bézier patch, from the Bernstein form of the
// squared distance: with X(s,t) the homogeneous numerator and W(s,t) the weight, |S − q|² = |X − q·W|² / W²,
// both products of two degree-(n, m) Bernstein polynomials, so degree (2n, 2m) with coefficients A_kl and
// W_kl (W_kl > 0 for positive weights). On [0,1]² a ratio of two such polynomials is at least the smallest
// ratio of their coefficients: |S − q|² >= min A_kl / W_kl. Unlike a bounding ball it is exact where the
// distance is constant — the centre of a rational sphere, where every subpatch ties and balls never prune.
// Internal.
#pragma once

#include "nurbs/binomial.h"
#include "unidist/nurbs.h"

#include <algorithm>
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
/// weights C(n,i)·C(n,k−i) / C(2n,k) sum to one over i, likewise in m), each unordered pair of points taken once.
/// y (net.size() entries) receives X_ij − q·W_ij. Coeffs: anything with assign(size, value) and operator[].
template <class Coeffs>
void squaredDistanceForm(const RationalBezierPatch& patch, const Eigen::Vector3d& q, Eigen::Vector3d* y, Coeffs& A,
                         Coeffs& W) {
  const int n = patch.degreeU, m = patch.degreeV;
  const std::size_t cols = static_cast<std::size_t>(2 * m + 1);
  A.assign(static_cast<std::size_t>(2 * n + 1) * cols, 0.0);
  W.assign(static_cast<std::size_t>(2 * n + 1) * cols, 0.0);
  double cu[kMaxNurbsDegree + 1], cv[kMaxNurbsDegree + 1], inverseU[2 * kMaxNurbsDegree + 1],
      inverseV[2 * kMaxNurbsDegree + 1];
  for (int i = 0; i <= n; ++i) cu[i] = binomial(n, i);
  for (int j = 0; j <= m; ++j) cv[j] = binomial(m, j);
  for (int k = 0; k <= 2 * n; ++k) inverseU[k] = 1 / binomial(2 * n, k);
  for (int l = 0; l <= 2 * m; ++l) inverseV[l] = 1 / binomial(2 * m, l);
  const int count = (n + 1) * (m + 1);
  for (int k = 0; k < count; ++k) y[k] = patch.net[static_cast<std::size_t>(k)].head<3>() - q * patch.net[static_cast<std::size_t>(k)][3];
  for (int k1 = 0; k1 < count; ++k1) {
    const int i = k1 / (m + 1), j = k1 % (m + 1);
    const double w1 = patch.net[static_cast<std::size_t>(k1)][3];
    for (int k2 = k1; k2 < count; ++k2) {
      const int i2 = k2 / (m + 1), j2 = k2 % (m + 1);
      const double f = (k2 == k1 ? 1.0 : 2.0) * cu[i] * cu[i2] * inverseU[i + i2] * cv[j] * cv[j2] * inverseV[j + j2];
      const std::size_t kl = static_cast<std::size_t>(i + i2) * cols + static_cast<std::size_t>(j + j2);
      A[kl] += f * y[k1].dot(y[k2]);
      W[kl] += f * w1 * patch.net[static_cast<std::size_t>(k2)][3];
    }
  }
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
