// The same-degree Bernstein products on binomial-scaled coefficients (core/src/nurbs/bernstein_product.h),
// checked against the polynomials' own values: the product and the square (each pair of distinct terms taken
// once), unscaled, evaluate to the product of the factors' values, at every degree the loops are unrolled for and
// at generic ones, with scalar and with vector coefficients (multiplied by the dot product).
#include "nurbs/bernstein_product.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace unidist::nurbs {
namespace {

/// The polynomial of degree (n, m) with Bernstein coefficients c (u-major) at (s, t).
template <class T>
T bernsteinValue(int n, int m, const std::vector<T>& c, double s, double t) {
  T value = 0 * c[0];
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= m; ++j)
      value += c[static_cast<std::size_t>(i * (m + 1) + j)] * (binomial(n, i) * std::pow(s, i) * std::pow(1 - s, n - i) *
                                                             binomial(m, j) * std::pow(t, j) * std::pow(1 - t, m - j));
  return value;
}

/// The form's coefficients times their binomials, as the products take them.
template <class T>
std::vector<T> scaled(int n, int m, const std::vector<T>& c) {
  std::vector<T> out = c;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= m; ++j) out[static_cast<std::size_t>(i * (m + 1) + j)] *= binomial(n, i) * binomial(m, j);
  return out;
}

TEST(BernsteinProduct, ProductsAndSquaresAreTheProductsOfTheValues) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (const auto& [n, m] : {std::pair{1, 1}, {2, 2}, {3, 3}, {4, 4}, {6, 6}, {2, 3}, {5, 5}, {1, 4}}) {
    SCOPED_TRACE(::testing::Message() << "degree " << n << ", " << m);
    const std::size_t terms = static_cast<std::size_t>((n + 1) * (m + 1));
    std::vector<double> x(terms), y(terms);
    std::vector<Eigen::Vector3d> v(terms), u(terms);
    for (std::size_t k = 0; k < terms; ++k) {
      x[k] = unit(rng);
      y[k] = unit(rng);
      v[k] = Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
      u[k] = Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
    }
    const std::vector<double> xs = scaled(n, m, x), ys = scaled(n, m, y);
    const std::vector<Eigen::Vector3d> vs = scaled(n, m, v), us = scaled(n, m, u);
    const double factor = unit(rng);
    const std::size_t out = static_cast<std::size_t>((2 * n + 1) * (2 * m + 1));
    // The products add to what is there: every (scaled) coefficient starts at 0.5, taken off before unscaling.
    std::vector<double> product(out, 0.5), square(out, 0.5), productV(out, 0.5), squareV(out, 0.5);
    addScaledProduct(n, m, xs.data(), ys.data(), factor, product.data());
    addScaledSquare(n, m, xs.data(), factor, square.data());
    addScaledProduct(n, m, vs.data(), us.data(), factor, productV.data());
    addScaledSquare(n, m, vs.data(), factor, squareV.data());
    for (auto* f : {&product, &square, &productV, &squareV}) {
      for (double& c : *f) c -= 0.5;
      unscaleByBinomials(2 * n, 2 * m, f->data());
    }
    for (double s : {0.0, 0.3, 0.77, 1.0})
      for (double t : {0.0, 0.5, 0.9}) {
        const double fx = bernsteinValue(n, m, x, s, t), fy = bernsteinValue(n, m, y, s, t);
        const Eigen::Vector3d fv = bernsteinValue(n, m, v, s, t), fu = bernsteinValue(n, m, u, s, t);
        EXPECT_NEAR(bernsteinValue(2 * n, 2 * m, product, s, t), factor * fx * fy, 1e-12);
        EXPECT_NEAR(bernsteinValue(2 * n, 2 * m, square, s, t), factor * fx * fx, 1e-12);
        EXPECT_NEAR(bernsteinValue(2 * n, 2 * m, productV, s, t), factor * fv.dot(fu), 1e-12);
        EXPECT_NEAR(bernsteinValue(2 * n, 2 * m, squareV, s, t), factor * fv.squaredNorm(), 1e-12);
      }
  }
}

}  // namespace
}  // namespace unidist::nurbs
