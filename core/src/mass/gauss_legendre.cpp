#include "mass/gauss_legendre.h"

#include <cmath>
#include <cstddef>

namespace unidist::mass {
namespace {

struct LegendreValue {
  double value, derivative;
};

/// P_n(x) and P_n'(x) for |x| < 1 by the three-term recurrence.
LegendreValue legendre(int n, double x) {
  double previous = 1, current = x;
  for (int k = 2; k <= n; ++k) {
    const double next = ((2 * k - 1) * x * current - (k - 1) * previous) / k;
    previous = current;
    current = next;
  }
  return {current, n * (x * current - previous) / (x * x - 1)};
}

}  // namespace

GaussRule gaussLegendre(int n) {
  constexpr double kPi = 3.14159265358979323846;
  GaussRule rule;
  rule.nodes.resize(static_cast<std::size_t>(n));
  rule.weights.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    // Root i of P_n (descending), Newton from the classical cosine estimate; it converges quadratically.
    double x = std::cos(kPi * (i + 0.75) / (n + 0.5));
    for (int iteration = 0; iteration < 100; ++iteration) {
      const LegendreValue p = legendre(n, x);
      const double step = p.value / p.derivative;
      x -= step;
      if (std::abs(step) <= 1e-16) break;
    }
    const double derivative = legendre(n, x).derivative;
    const auto at = static_cast<std::size_t>(i);
    rule.nodes[at] = 0.5 * (1 - x);                                  // ascending on [0, 1]
    rule.weights[at] = 1 / ((1 - x * x) * derivative * derivative);  // 2 / ((1 − x²) P_n'²), halved for [0, 1]
  }
  return rule;
}

}  // namespace unidist::mass
