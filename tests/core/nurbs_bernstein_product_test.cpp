// The same-degree Bernstein products on binomial-scaled coefficients (core/src/nurbs/bernstein_product.h): the
// square taking each pair of distinct terms once (addScaledSquare) is the plain product of a form with itself,
// for scalar and vector coefficients, at every unrolled degree and the generic one; and a product, unscaled, is
// the product of the two polynomials' values.
#include "nurbs/bernstein_product.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace unidist::nurbs {
namespace {

/// The polynomial of degree (n, m) with Bernstein coefficients c (u-major) at (s, t).
double bernsteinValue(int n, int m, const std::vector<double>& c, double s, double t) {
  double value = 0;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= m; ++j)
      value += c[static_cast<std::size_t>(i * (m + 1) + j)] * binomial(n, i) * std::pow(s, i) * std::pow(1 - s, n - i) *
               binomial(m, j) * std::pow(t, j) * std::pow(1 - t, m - j);
  return value;
}

TEST(BernsteinProduct, SquareIsTheProductOfAFormWithItself) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(-2, 2);
  for (const auto& [n, m] : {std::pair{1, 1}, {2, 2}, {3, 3}, {4, 4}, {6, 6}, {2, 3}, {5, 5}, {1, 4}}) {
    SCOPED_TRACE(::testing::Message() << "degree " << n << ", " << m);
    const std::size_t terms = static_cast<std::size_t>((n + 1) * (m + 1));
    const std::size_t out = static_cast<std::size_t>((2 * n + 1) * (2 * m + 1));
    std::vector<double> x(terms);
    std::vector<Eigen::Vector3d> v(terms);
    for (std::size_t k = 0; k < terms; ++k) {
      x[k] = unit(rng);
      v[k] = Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
    }
    const double factor = unit(rng);
    std::vector<double> square(out, 0.5), product(out, 0.5), squareV(out, 0.0), productV(out, 0.0);
    addScaledSquare(n, m, x.data(), factor, square.data());
    addScaledProduct(n, m, x.data(), x.data(), factor, product.data());
    addScaledSquare(n, m, v.data(), factor, squareV.data());
    addScaledProduct(n, m, v.data(), v.data(), factor, productV.data());
    for (std::size_t k = 0; k < out; ++k) {
      EXPECT_NEAR(square[k], product[k], 1e-12 * (1 + std::abs(product[k])));
      EXPECT_NEAR(squareV[k], productV[k], 1e-12 * (1 + std::abs(productV[k])));
    }
  }
}

TEST(BernsteinProduct, UnscaledProductIsTheProductOfTheValues) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (const auto& [n, m] : {std::pair{2, 2}, {4, 4}, {2, 3}}) {
    const std::size_t terms = static_cast<std::size_t>((n + 1) * (m + 1));
    std::vector<double> x(terms), y(terms), xs(terms), ys(terms);
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= m; ++j) {
        const auto k = static_cast<std::size_t>(i * (m + 1) + j);
        x[k] = unit(rng);
        y[k] = unit(rng);
        xs[k] = binomial(n, i) * binomial(m, j) * x[k];  // the scaled forms the products take
        ys[k] = binomial(n, i) * binomial(m, j) * y[k];
      }
    std::vector<double> product(static_cast<std::size_t>((2 * n + 1) * (2 * m + 1)), 0.0), square = product;
    addScaledProduct(n, m, xs.data(), ys.data(), -3.0, product.data());
    addScaledSquare(n, m, xs.data(), 2.0, square.data());
    unscaleByBinomials(2 * n, 2 * m, product.data());
    unscaleByBinomials(2 * n, 2 * m, square.data());
    for (double s : {0.0, 0.3, 0.77, 1.0})
      for (double t : {0.0, 0.5, 0.9}) {
        const double fx = bernsteinValue(n, m, x, s, t), fy = bernsteinValue(n, m, y, s, t);
        EXPECT_NEAR(bernsteinValue(2 * n, 2 * m, product, s, t), -3.0 * fx * fy, 1e-12);
        EXPECT_NEAR(bernsteinValue(2 * n, 2 * m, square, s, t), 2.0 * fx * fx, 1e-12);
      }
  }
}

}  // namespace
}  // namespace unidist::nurbs
