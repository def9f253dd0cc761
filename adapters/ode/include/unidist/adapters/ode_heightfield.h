// An ODE heightfield as a closed core TriangleMesh (for the ODE plugin's unidist::ode::describeHeightfield).
// ODE 0.16 gives no public access to a dHeightfieldDataID's samples, so the caller passes the same numbers it
// gave dGeomHeightfieldDataBuildDouble; this file only turns them into a mesh in the heightfield geom's frame.
//
// ODE's heightfield frame: Y up, centred on the origin. Sample (i, j), i < widthSamples along x and
// j < depthSamples along z, is heights[i + j·widthSamples] and sits at
//   x = −width/2 + i·width/(widthSamples − 1),  z = −depth/2 + j·depth/(depthSamples − 1),
//   y = heights[i + j·widthSamples]·scale + offset.
// Each cell (i, j)…(i+1, j+1) is split along the diagonal from (i+1, j) to (i, j+1) (ODE's two triangles: the
// one holding (i, j) and the one holding (i+1, j+1)). The mesh is that surface closed by four vertical side
// walls and a flat bottom at (lowest height − thickness): a solid, so that "inside" and penetration depth are
// defined for bodies that sink into the terrain.
#pragma once

#include "unidist/mesh.h"

#include <memory>

namespace unidist {

/// dGeomHeightfieldDataBuildDouble's numbers (without the copy flag: the mesh is always a copy).
struct OdeHeightfieldSpec {
  const double* heights = nullptr;  ///< widthSamples × depthSamples values, x fastest
  double width = 0, depth = 0;      ///< extent along local x and z (> 0)
  int widthSamples = 0, depthSamples = 0;  ///< >= 2 each
  double scale = 1, offset = 0;     ///< height = sample·scale + offset (finite)
  double thickness = 0;             ///< the solid reaches down to the lowest height − thickness (> 0)
  bool wrap = false;                ///< ODE's infinite tiling: not supported (InputError)
};

/// Validates the spec (InputError naming the bad argument: null heights, fewer than 2 samples, a width, depth
/// or thickness that is not finite and > 0, a non-finite scale or offset, a NaN or infinite sample, wrap) and
/// builds the closed mesh described above. Triangles 0 … 2·(W−1)·(D−1) − 1 are the surface, cell by cell (x
/// fastest), the triangle holding (i, j) first; the walls and the bottom follow.
std::shared_ptr<const TriangleMesh> odeHeightfieldMesh(const OdeHeightfieldSpec& spec);

}  // namespace unidist
