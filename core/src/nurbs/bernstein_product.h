// The product of two polynomials in tensor-product Bernstein form, coefficient pairs combined by a given
// function (a dot product, a scaling): shared by the gradient and curvature forms of the point query's proofs
// (gradient_sign.h, point_convexity.h). Internal.
#pragma once

#include "nurbs/binomial.h"

#include <Eigen/Core>

#include <vector>

namespace unidist::nurbs {

/// Bernstein coefficients of the product of a degree-(n, m) polynomial (coefficients x, u-major) and a
/// degree-(a, b) one (y), each coefficient pair combined by mul, into `out` (degree (n + a, m + b), u-major).
/// n and m at most kMaxNurbsDegree, a and b at most twice that.
template <class T, class X, class Y, class Mul>
inline void product(int n, int m, const std::vector<X>& x, int a, int b, const std::vector<Y>& y, Mul mul, const T& zero,
             std::vector<T>& out) {
  // The weights C(n,i) C(a,k) / C(n+a,i+k) once per direction (a product runs per new node).
  double fu[kMaxNurbsDegree + 1][2 * kMaxNurbsDegree + 1], fv[kMaxNurbsDegree + 1][2 * kMaxNurbsDegree + 1];
  for (int i = 0; i <= n; ++i)
    for (int k = 0; k <= a; ++k) fu[i][k] = binomial(n, i) * binomial(a, k) / binomial(n + a, i + k);
  for (int j = 0; j <= m; ++j)
    for (int l = 0; l <= b; ++l) fv[j][l] = binomial(m, j) * binomial(b, l) / binomial(m + b, j + l);
  const int cols = m + b + 1;
  out.assign(static_cast<std::size_t>((n + a + 1) * cols), zero);
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= m; ++j) {
      const X& xi = x[static_cast<std::size_t>(i * (m + 1) + j)];
      for (int k = 0; k <= a; ++k) {
        T* row = &out[static_cast<std::size_t>((i + k) * cols + j)];
        const Y* yk = &y[static_cast<std::size_t>(k * (b + 1))];
        const double f = fu[i][k];
        for (int l = 0; l <= b; ++l) row[l] += (f * fv[j][l]) * mul(xi, yk[l]);
      }
    }
}

/// The usual ways to combine coefficient pairs.
inline double dotOf(const Eigen::Vector3d& x, const Eigen::Vector3d& y) { return x.dot(y); }
inline Eigen::Vector3d scaledBy(double w, const Eigen::Vector3d& y) { return w * y; }

}  // namespace unidist::nurbs
