// unidist::bullet — Bullet plugin (shell for now: later issues add the shapes and collision algorithms).
#pragma once

#include <string>

namespace unidist::bullet {

/// Bullet version the plugin was compiled against (btGetVersion(), e.g. 324 → "3.24"), and its scalar width.
std::string engineVersion();

}  // namespace unidist::bullet
