// Kim et al.'s multi-pass stencil/depth rendering of the boundary of a union of convex pieces seen from a point
// inside it, one cube face at a time (internal). Each pixel ends with the farthest depth reachable from the
// eye through overlapping pieces and the id of the back facet that set it.
#pragma once

#include "cube_views.h"
#include "unidist/raster/offscreen_context.h"

#include <cstdint>
#include <vector>

namespace unidist::raster::detail {

/// A piece ready to draw: triangles relative to the eye, each carrying its facet id as an RGBA colour.
struct RenderablePiece {
  std::vector<float> xyz;            ///< 9 floats per triangle
  std::vector<unsigned char> rgba;   ///< 12 bytes per triangle: id + 1, little-endian, once per vertex
  Aabb box;                          ///< relative to the eye
  bool containsEye = false;          ///< rendered once, back faces with the greater-depth test
  double maxDistance = 0;            ///< farthest vertex from the eye
};

/// One view's result: window depth (0 where nothing was drawn) and id + 1 (0: none), bottom row first.
struct ViewImage {
  std::vector<float> depth;
  std::vector<std::uint32_t> ids;
  double nearPlane = 0, farPlane = 0;
  int passes = 0, rendered = 0, culled = 0;
  /// Euclidean distance from the eye along the ray through pixel (i, j) for window depth d.
  double distance(const CubeView& view, int n, int i, int j, double d) const {
    const double eyeDepth = farPlane * nearPlane / (farPlane - d * (farPlane - nearPlane));
    return eyeDepth * view.pixelRay(n, i, j).norm();
  }
};

/// Renders on a context made current at resolution²; saves the GL state it changes and restores it on exit.
class BoundaryRenderer {
 public:
  BoundaryRenderer(OffscreenContext& context, int resolution);
  ~BoundaryRenderer();
  BoundaryRenderer(const BoundaryRenderer&) = delete;
  BoundaryRenderer& operator=(const BoundaryRenderer&) = delete;

  /// `order`: the pieces not containing the eye, nearest first (chains of overlaps then settle in few passes).
  /// nearPlane must not exceed the eye depth of any boundary point (it clips nothing that matters: front faces
  /// nearer than it cannot block a window, back faces nearer than it lie inside the containing pieces).
  ViewImage render(const CubeView& view, const std::vector<RenderablePiece>& pieces, const std::vector<int>& order,
                   double nearPlane, int maxPasses);

 private:
  int resolution_;
  std::vector<unsigned int> queries_;
};

}  // namespace unidist::raster::detail
