// The display tessellation's parts: primitives (tessellate_primitives.cpp) and the models with data of their
// own (tessellate_models.cpp, which also dispatches).
#pragma once

#include "unidist/primitives.h"
#include "unidist/render/display_mesh.h"
#include "unidist/types.h"

#include <algorithm>
#include <string>

namespace unidist::render {

DisplayMesh tessellatePrimitive(const Model& model, const TessellationOptions& options);

}  // namespace unidist::render
