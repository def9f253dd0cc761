#include "unidist/bullet/version.h"

#include <LinearMath/btScalar.h>

namespace unidist::bullet {

std::string engineVersion() {
  const int v = btGetVersion();
  return "Bullet " + std::to_string(v / 100) + "." + std::to_string(v % 100) +
         (sizeof(btScalar) == sizeof(double) ? " (double)" : " (float)");
}

}  // namespace unidist::bullet
