// B-spline building blocks on one parameter direction: knot spans, basis functions with derivatives, and
// knot insertion up to Bézier form. Internal to the NURBS model.
#pragma once

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

/// Bernstein polynomials of degree n at t and their first two derivatives: out[k][i].
void bernstein(int n, double t, std::array<std::array<double, 32>, 3>& out);

/// A curve of homogeneous points cut into Bézier segments by knot insertion: segments[k] holds p + 1 points
/// over [breaks[k], breaks[k+1]].
struct BezierSegments {
  std::vector<double> breaks;
  std::vector<std::vector<Eigen::Vector4d>> segments;
};

/// Inserts knots (Boehm) until every distinct knot of the domain [t_p, t_n] has multiplicity at least p.
BezierSegments toBezierSegments(std::vector<double> knots, int p, std::vector<Eigen::Vector4d> points);

}  // namespace unidist::nurbs
