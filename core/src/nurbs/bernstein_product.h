// The product of two polynomials in tensor-product Bernstein form, coefficient pairs combined by a given
// function (a dot product, a scaling): shared by the gradient and curvature forms of the point query's proofs
// (gradient_sign.h, point_convexity.h). And the same-degree product on binomial-scaled coefficients, one
// multiply-add a term, for the forms made per node of every query (the squared distance, the tube's quartic).
// Internal.
#pragma once

#include "nurbs/binomial.h"

#include <Eigen/Core>

#include <type_traits>
#include <vector>

// GCC unrolls the fixed-degree products' loops fully on request; Clang refuses some of them with a warning (an
// error here), so it is left to its own judgement. GCC 12 with -fsanitize=undefined crashes in that unrolling
// (an internal compiler error), and GCC defines no macro for that sanitizer: the sanitizer builds define
// UNIDIST_NO_UNROLL (CMakeLists.txt), as a build of one's own with it must.
#if defined(__GNUC__) && !defined(__clang__) && !defined(UNIDIST_NO_UNROLL)
#define UNIDIST_PRAGMA(text) _Pragma(#text)
#define UNIDIST_UNROLL(count) UNIDIST_PRAGMA(GCC unroll count)
#else
#define UNIDIST_UNROLL(count)
#endif

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
inline double timesOf(const Eigen::Vector3d& x, const Eigen::Vector3d& y) { return x.dot(y); }
inline Eigen::Vector3d scaledBy(double w, const Eigen::Vector3d& y) { return w * y; }

inline double timesOf(double x, double y) { return x * y; }

namespace detail {

/// Calls body(std::integral_constant<int, N>{}) with N = n where n == m is a degree the loops are unrolled for
/// (the forms of patches of degree 1 to 3 and their squares), else with N = −1 (n and m at run time).
template <class Body>
inline void withUnrolledDegree(int n, int m, Body&& body) {
  switch (n == m ? n : -1) {
    case 1: return body(std::integral_constant<int, 1>{});
    case 2: return body(std::integral_constant<int, 2>{});
    case 3: return body(std::integral_constant<int, 3>{});
    case 4: return body(std::integral_constant<int, 4>{});
    case 6: return body(std::integral_constant<int, 6>{});
    default: return body(std::integral_constant<int, -1>{});
  }
}

/// addScaledProduct (y: the second form) or, with Square, addScaledSquare (y unused) at run-time degrees. __restrict:
/// the output never overlaps the inputs, so the compiler need not reload them after every store.
template <bool Square, class T>
inline void addScaledProductOf(int n, int m, const T* __restrict x, const T* __restrict y, double factor,
                               double* __restrict out) {
  const int cols = 2 * m + 1;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= m; ++j) {
      const T xij = factor * x[i * (m + 1) + j];
      if constexpr (Square) {  // the term with itself once, every later term (in u-major order) twice
        const T twice = 2 * xij;
        double* row = out + 2 * i * cols + j;
        const T* xi = x + i * (m + 1);
        row[j] += timesOf(xij, xi[j]);
        for (int l = j + 1; l <= m; ++l) row[l] += timesOf(twice, xi[l]);
        for (int k = i + 1; k <= n; ++k) {
          double* rowK = out + (i + k) * cols + j;
          const T* xk = x + k * (m + 1);
          for (int l = 0; l <= m; ++l) rowK[l] += timesOf(twice, xk[l]);
        }
      } else {
        for (int k = 0; k <= n; ++k) {
          double* row = out + (i + k) * cols + j;
          const T* yk = y + k * (m + 1);
          for (int l = 0; l <= m; ++l) row[l] += timesOf(xij, yk[l]);
        }
      }
    }
}

/// The same at degree (N, N) known at compile time, each output coefficient summed in a register over its terms
/// (loops fully unrolled: about two thirds of the instructions of the loops above).
template <int N, bool Square, class T>
inline void addScaledProductOf(const T* __restrict x, const T* __restrict y, double factor, double* __restrict out) {
  constexpr int kCols = 2 * N + 1;
UNIDIST_UNROLL(16)
  for (int r = 0; r < kCols; ++r) {
UNIDIST_UNROLL(16)
    for (int c = 0; c < kCols; ++c) {
      double sum = 0, own = 0;  // own: a square's term with itself
UNIDIST_UNROLL(8)
      for (int i = (r > N ? r - N : 0); i <= (r < N ? r : N); ++i)
UNIDIST_UNROLL(8)
        for (int j = (c > N ? c - N : 0); j <= (c < N ? c : N); ++j) {
          const int a = i * (N + 1) + j, b = (r - i) * (N + 1) + c - j;
          if constexpr (Square) {
            if (a < b) sum += timesOf(x[a], x[b]);
            else if (a == b) own = timesOf(x[a], x[a]);
          } else {
            sum += timesOf(x[a], y[b]);
          }
        }
      out[r * kCols + c] += factor * (Square ? 2 * sum + own : sum);
    }
  }
}

}  // namespace detail

/// The product of two degree-(n, m) forms (T: double, or Eigen::Vector3d multiplied by the dot product) held
/// scaled by their binomials (x̃_ij = C(n,i)·C(m,j)·x_ij), times `factor`, added to `out`: degree (2n, 2m), scaled
/// the same way. With the binomials folded in, every term is one product; unscaleByBinomials turns the sums into
/// plain coefficients (each then a mean of products, as `product` computes them).
template <class T>
inline void addScaledProduct(int n, int m, const T* x, const T* y, double factor, double* out) {
  detail::withUnrolledDegree(n, m, [&](auto N) {
    if constexpr (N() >= 0) detail::addScaledProductOf<N(), false>(x, y, factor, out);
    else detail::addScaledProductOf<false>(n, m, x, y, factor, out);
  });
}

/// addScaledProduct(n, m, x, x, factor, out), each pair of distinct terms taken once and doubled (half the
/// products).
template <class T>
inline void addScaledSquare(int n, int m, const T* x, double factor, double* out) {
  detail::withUnrolledDegree(n, m, [&](auto N) {
    if constexpr (N() >= 0) detail::addScaledProductOf<N(), true>(x, x, factor, out);
    else detail::addScaledProductOf<true>(n, m, x, x, factor, out);
  });
}

/// Coefficients of degree (n, m) held scaled by their binomials, divided back: c_ij / (C(n,i)·C(m,j)).
inline void unscaleByBinomials(int n, int m, double* c) {
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= m; ++j) c[i * (m + 1) + j] /= binomial(n, i) * binomial(m, j);
}

}  // namespace unidist::nurbs

#undef UNIDIST_UNROLL
#undef UNIDIST_PRAGMA
