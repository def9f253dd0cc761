// Binomial coefficients for the Bernstein products of the patch tree and the gradient certificate: one table,
// built on first use and read-only after. Internal.
#pragma once

#include "unidist/nurbs.h"

#include <cstddef>
#include <vector>

namespace unidist::nurbs {

/// C(n, k) for 0 <= k <= n <= 3 kMaxNurbsDegree (rounded to a few ulps beyond 2^53, which only scales a
/// coefficient by a positive factor that close to 1).
inline double binomial(int n, int k) {
  static const std::vector<std::vector<double>> table = [] {
    std::vector<std::vector<double>> t(3 * kMaxNurbsDegree + 1);
    for (std::size_t m = 0; m < t.size(); ++m) {
      t[m].assign(m + 1, 1.0);
      for (std::size_t j = 1; j < m; ++j) t[m][j] = t[m - 1][j - 1] + t[m - 1][j];
    }
    return t;
  }();
  return table[static_cast<std::size_t>(n)][static_cast<std::size_t>(k)];
}

}  // namespace unidist::nurbs
