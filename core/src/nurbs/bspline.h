// B-spline building blocks on one parameter direction: knot spans, basis functions with derivatives, and
// knot insertion up to Bézier form. Internal to the NURBS model.
#pragma once

#include "nurbs/binomial.h"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace unidist::nurbs {

/// Basis values and their first two derivatives for the p + 1 functions N_{span-p..span, p} at u.
struct BasisRow {
  int span = 0;
  std::array<std::array<double, 32>, 3> d{};  // d[k][j] = k-th derivative of N_{span-p+j, p}(u)
};

/// The span s in [p, n-1] with t_s <= u < t_{s+1}; u at or beyond the domain end maps to the last non-empty span.
int findSpan(const std::vector<double>& knots, int p, int n, double u);

/// Non-zero basis functions of degree p at u and their first and second derivatives.
BasisRow basisWithDerivatives(const std::vector<double>& knots, int p, int span, double u);

/// Bernstein polynomials of degree n at t and their first two derivatives: out[k][i] (out: three rows of at
/// least n + 1). Power form B_i^m = C(m,i) t^i (1−t)^(m−i) for m = n, n−1, n−2, a few multiplications per value
/// (the Newton polish spends most of its time here); B' and B'' from the lower degrees. Inline, so a caller
/// whose n is a constant gets the loops unrolled.
template <class Rows>
inline void bernstein(int n, double t, Rows& out) {
  double tp[kMaxNurbsDegree + 1], sp[kMaxNurbsDegree + 1];
  tp[0] = sp[0] = 1.0;
  const double s = 1.0 - t;
  for (int k = 1; k <= n; ++k) {
    tp[k] = tp[k - 1] * t;
    sp[k] = sp[k - 1] * s;
  }
  const auto B = [&](int m, int i) { return m < 0 || i < 0 || i > m ? 0.0 : binomial(m, i) * tp[i] * sp[m - i]; };
  for (int i = 0; i <= n; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    out[0][ui] = B(n, i);
    out[1][ui] = n * (B(n - 1, i - 1) - B(n - 1, i));
    out[2][ui] = n * (n - 1) * (B(n - 2, i - 2) - 2 * B(n - 2, i - 1) + B(n - 2, i));
  }
}

/// A curve of homogeneous points cut into Bézier segments by knot insertion: segments[k] holds p + 1 points
/// over [breaks[k], breaks[k+1]].
struct BezierSegments {
  std::vector<double> breaks;
  std::vector<std::vector<Eigen::Vector4d>> segments;
};

/// Inserts knots (Boehm) until every distinct knot of the domain [t_p, t_n] has multiplicity at least p.
BezierSegments toBezierSegments(std::vector<double> knots, int p, std::vector<Eigen::Vector4d> points);

/// The same curve over [a, b] (t_p <= a < b <= t_n): a and b inserted (Boehm) up to multiplicity p, the points
/// and knots beyond them dropped and the new ends clamped (p + 1 equal knots). Parameters keep their values.
void restrictCurve(std::vector<double>& knots, int p, std::vector<Eigen::Vector4d>& points, double a, double b);

}  // namespace unidist::nurbs
