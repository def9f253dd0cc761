// The rounding part of a contact's error bound (internal).
#pragma once

#include "unidist/contacts.h"

#include <limits>

namespace unidist::contact {

/// What double rounding can add to a contact computed in closed form from its points: a few dozen operations on
/// coordinates of the points' magnitude (poses composed, differences, a square root).
inline double roundingBound(const Contact& c) {
  const double scale = std::max(c.pointA.cwiseAbs().maxCoeff(), c.pointB.cwiseAbs().maxCoeff()) + std::abs(c.distance);
  return 64 * std::numeric_limits<double>::epsilon() * scale;
}

}  // namespace unidist::contact
