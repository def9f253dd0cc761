// unidist::ode — ODE plugin (shell for now: later issues add the geom class and its colliders).
#pragma once

#include <string>

namespace unidist::ode {

/// ODE's build configuration (dGetConfiguration(), e.g. "ODE_EXT_trimesh ... ODE_double_precision").
std::string engineConfiguration();

}  // namespace unidist::ode
