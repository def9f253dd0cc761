#include "nurbs/bspline.h"

#include <algorithm>

namespace unidist::nurbs {

int findSpan(const std::vector<double>& knots, int p, int n, double u) {
  const auto k = [&](int i) { return knots[static_cast<std::size_t>(i)]; };
  if (u >= k(n)) {  // the domain end belongs to the last non-empty span
    int s = n - 1;
    while (s > p && k(s) >= k(n)) --s;
    return s;
  }
  if (u <= k(p)) {
    int s = p;
    while (s < n - 1 && k(s + 1) <= k(p)) ++s;
    return s;
  }
  // Largest s in [p, n-1] with t_s <= u: binary search on the sorted knots.
  const auto first = knots.begin() + p, last = knots.begin() + n;
  const int s = static_cast<int>(std::upper_bound(first, last, u) - knots.begin()) - 1;
  return std::clamp(s, p, n - 1);
}

BasisRow basisWithDerivatives(const std::vector<double>& knots, int p, int span, double u) {
  const auto k = [&](int i) { return knots[static_cast<std::size_t>(i)]; };
  // table[d][j] = N_{span-d+j, d}(u), the non-zero functions of every degree d <= p (Cox–de Boor).
  std::array<std::array<double, 32>, 32> table{};
  table[0][0] = 1.0;
  for (int d = 1; d <= p; ++d) {
    for (int j = 0; j <= d; ++j) {
      const int i = span - d + j;
      double value = 0;
      if (j >= 1) {  // left term uses N_{i, d-1} = table[d-1][j-1]
        const double den = k(i + d) - k(i);
        if (den > 0) value += (u - k(i)) / den * table[static_cast<std::size_t>(d - 1)][static_cast<std::size_t>(j - 1)];
      }
      if (j <= d - 1) {  // right term uses N_{i+1, d-1} = table[d-1][j]
        const double den = k(i + d + 1) - k(i + 1);
        if (den > 0) value += (k(i + d + 1) - u) / den * table[static_cast<std::size_t>(d - 1)][static_cast<std::size_t>(j)];
      }
      table[static_cast<std::size_t>(d)][static_cast<std::size_t>(j)] = value;
    }
  }
  // D^m N_{i,d} = d/(t_{i+d}-t_i) D^{m-1} N_{i,d-1} − d/(t_{i+d+1}-t_{i+1}) D^{m-1} N_{i+1,d-1}; 0/0 = 0.
  const auto value = [&](auto&& self, int m, int d, int i) -> double {
    if (i < span - d || i > span) return 0.0;
    if (m == 0) return table[static_cast<std::size_t>(d)][static_cast<std::size_t>(i - span + d)];
    if (d == 0) return 0.0;
    double out = 0;
    const double left = k(i + d) - k(i), right = k(i + d + 1) - k(i + 1);
    if (left > 0) out += d / left * self(self, m - 1, d - 1, i);
    if (right > 0) out -= d / right * self(self, m - 1, d - 1, i + 1);
    return out;
  };
  BasisRow row;
  row.span = span;
  for (int m = 0; m <= 2; ++m)
    for (int j = 0; j <= p; ++j)
      row.d[static_cast<std::size_t>(m)][static_cast<std::size_t>(j)] = value(value, m, p, span - p + j);
  return row;
}

namespace {

/// Boehm: inserts u once into the curve (knots, points) of degree p, using span k with t_k <= u <= t_{k+1}, t_k < t_{k+1}.
void insertKnot(std::vector<double>& knots, std::vector<Eigen::Vector4d>& points, int p, int k, double u) {
  std::vector<Eigen::Vector4d> out(points.size() + 1);
  for (int i = 0; i <= static_cast<int>(points.size()); ++i) {
    const auto ui = static_cast<std::size_t>(i);
    if (i <= k - p) {
      out[ui] = points[ui];
    } else if (i >= k + 1) {
      out[ui] = points[ui - 1];
    } else {
      const double a = (u - knots[ui]) / (knots[ui + static_cast<std::size_t>(p)] - knots[ui]);
      out[ui] = a * points[ui] + (1 - a) * points[ui - 1];
    }
  }
  knots.insert(knots.begin() + k + 1, u);
  points = std::move(out);
}

}  // namespace

BezierSegments toBezierSegments(std::vector<double> knots, int p, std::vector<Eigen::Vector4d> points) {
  const auto n = [&] { return static_cast<int>(points.size()); };
  const double a = knots[static_cast<std::size_t>(p)], b = knots[static_cast<std::size_t>(n())];
  std::vector<double> values;
  for (double t : knots)
    if (t >= a && t <= b && (values.empty() || t > values.back())) values.push_back(t);
  for (double u : values) {
    const int have = static_cast<int>(std::count(knots.begin(), knots.end(), u));
    for (int m = have; m < p; ++m) {
      // Span with t_k <= u <= t_{k+1} and t_k < t_{k+1}: the one ending at u for the domain end, else starting there.
      int k = u >= b ? findSpan(knots, p, n(), b) : findSpan(knots, p, n(), u);
      insertKnot(knots, points, p, k, u);
    }
  }
  BezierSegments out;
  for (int s = p; s < n(); ++s) {
    const double lo = knots[static_cast<std::size_t>(s)], hi = knots[static_cast<std::size_t>(s + 1)];
    if (!(hi > lo)) continue;
    out.breaks.push_back(lo);
    out.segments.emplace_back(points.begin() + (s - p), points.begin() + (s + 1));
  }
  out.breaks.push_back(b);
  return out;
}

void restrictCurve(std::vector<double>& knots, int p, std::vector<Eigen::Vector4d>& points, double a, double b) {
  const auto n = [&] { return static_cast<int>(points.size()); };
  const double end = knots[static_cast<std::size_t>(n())];
  for (double u : {a, b}) {
    const int have = static_cast<int>(std::count(knots.begin(), knots.end(), u));
    for (int m = have; m < p; ++m) insertKnot(knots, points, p, u >= end ? findSpan(knots, p, n(), end) : findSpan(knots, p, n(), u), u);
  }
  // With a of multiplicity >= p, point (last index of a) − p is the curve's point at a and starts the curve over
  // [a, ...]; with b's, point (first index of b) − 1 ends it.
  const auto lastA = std::upper_bound(knots.begin(), knots.end(), a) - knots.begin() - 1;
  const auto firstB = std::lower_bound(knots.begin(), knots.end(), b) - knots.begin();
  std::vector<double> kept(static_cast<std::size_t>(p + 1), a);
  kept.insert(kept.end(), knots.begin() + lastA + 1, knots.begin() + firstB);
  kept.insert(kept.end(), static_cast<std::size_t>(p + 1), b);
  points = std::vector<Eigen::Vector4d>(points.begin() + (lastA - p), points.begin() + firstB);
  knots = std::move(kept);
}

}  // namespace unidist::nurbs
