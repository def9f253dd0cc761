// The six 90° views around a point (the faces of a cube centred on it) and their pixel rays (internal).
#pragma once

#include "unidist/types.h"

#include <array>
#include <cmath>

namespace unidist::raster::detail {

/// One cube face: it looks along `axis`; `right` and `up` span the image (right × up = −axis, OpenGL's eye frame).
struct CubeView {
  Eigen::Vector3d axis, right, up;

  /// The ray through the centre of pixel (column i, row j from the bottom) of an n × n image, not normalised:
  /// its component along axis is 1, so its length is 1/cos of its angle to the axis.
  Eigen::Vector3d pixelRay(int n, int i, int j) const {
    const double x = (2.0 * i + 1.0) / n - 1.0, y = (2.0 * j + 1.0) / n - 1.0;
    return x * right + y * up + axis;
  }

  /// The box (relative to the eye) lies wholly outside one of the four side planes of the view's pyramid.
  bool culls(const Aabb& box) const {
    bool outside[4] = {true, true, true, true};
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3d p((c & 1) ? box.max.x() : box.min.x(), (c & 2) ? box.max.y() : box.min.y(),
                              (c & 4) ? box.max.z() : box.min.z());
      const double depth = axis.dot(p), x = right.dot(p), y = up.dot(p);
      outside[0] = outside[0] && x > depth;
      outside[1] = outside[1] && -x > depth;
      outside[2] = outside[2] && y > depth;
      outside[3] = outside[3] && -y > depth;
    }
    return outside[0] || outside[1] || outside[2] || outside[3];
  }
};

inline std::array<CubeView, 6> cubeViews() {
  std::array<CubeView, 6> views;
  const Eigen::Vector3d axes[6] = {Eigen::Vector3d::UnitX(), -Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                                   -Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ(), -Eigen::Vector3d::UnitZ()};
  for (int v = 0; v < 6; ++v) {
    views[v].axis = axes[v];
    views[v].up = v < 4 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitY();
    views[v].right = views[v].up.cross(-axes[v]);
  }
  return views;
}

/// The largest angle between any direction and the nearest pixel-centre ray of n × n cube faces: a direction
/// meets its face's plane (at distance 1) within half a pixel diagonal, √2/n, of a pixel centre, and the angle
/// between two rays to that plane is at most the arcsine of that distance.
inline double cubeAngularSpacing(int n) { return std::asin(std::min(1.0, std::sqrt(2.0) / n)); }

}  // namespace unidist::raster::detail
