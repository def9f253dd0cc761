#include "unidist/ode/version.h"

#include <ode/ode.h>

namespace unidist::ode {

std::string engineConfiguration() { return dGetConfiguration(); }

}  // namespace unidist::ode
