// The one check every loaded model passes before the core sees it: every tolerance is relative to the bounding
// box diagonal, so a finite model whose extent overflows a double (sphere:r=1e308; points at +-1e200) is refused.
#pragma once

#include "unidist/model.h"

#include <cmath>
#include <string>

namespace unidist {

/// Throws InputError "<name>: too large (...)" when the model is bounded by design but its diagonal is not finite.
inline void requireFiniteExtent(const Model& model, const std::string& name) {
  if (model.type() != ModelType::Plane && !std::isfinite(model.localBounds().diagonal()))
    throw InputError(name + ": too large (its bounding box diagonal overflows a double)");
}

}  // namespace unidist
