// Binomial coefficients for the NURBS code (Bernstein bases, products and derivatives): one table, computed at
// compile time, so a lookup with constant arguments folds to its value. Internal.
#pragma once

#include "unidist/nurbs.h"

namespace unidist::nurbs {

namespace detail {
constexpr int kBinomialRows = 3 * kMaxNurbsDegree + 1;  // products of three degree-n factors
struct BinomialTable {
  double c[kBinomialRows][kBinomialRows];
};
/// Pascal's triangle in doubles (exact up to 2^53; beyond, rounded a few ulps, which only scales a coefficient
/// by a positive factor that close to 1).
constexpr BinomialTable makeBinomialTable() {
  BinomialTable t{};
  for (int m = 0; m < kBinomialRows; ++m) {
    t.c[m][0] = t.c[m][m] = 1.0;
    for (int j = 1; j < m; ++j) t.c[m][j] = t.c[m - 1][j - 1] + t.c[m - 1][j];
  }
  return t;
}
inline constexpr BinomialTable kBinomial = makeBinomialTable();
}  // namespace detail

/// C(n, k) for 0 <= k <= n <= 3 kMaxNurbsDegree.
constexpr double binomial(int n, int k) { return detail::kBinomial.c[n][k]; }

}  // namespace unidist::nurbs
