// Gauss–Legendre rules on [0, 1]: n nodes integrate polynomials of degree 2n − 1 exactly.
#pragma once

#include <vector>

namespace unidist::mass {

struct GaussRule {
  std::vector<double> nodes, weights;  ///< nodes in (0, 1), weights summing to 1
};

/// The n-point rule (n >= 1), nodes by Newton's method on the Legendre polynomial to full double precision.
GaussRule gaussLegendre(int n);

}  // namespace unidist::mass
