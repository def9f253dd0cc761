// A perspective camera for the pictures: where it is, what it looks at, and the OpenGL matrices it makes.
#pragma once

#include "unidist/types.h"

#include <Eigen/Geometry>

#include <optional>

namespace unidist::render {

struct Camera {
  Eigen::Vector3d eye = Eigen::Vector3d(0, -5, 2);
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();  ///< world direction shown upward
  double fovY = 0.5236;                           ///< vertical field of view, radians (30°)
  double nearDistance = 0.1, farDistance = 100;   ///< clipping distances along the view direction, 0 < near < far

  /// World → eye (OpenGL's modelview of the world), column-major like OpenGL.
  Eigen::Matrix4d view() const;
  /// Eye → clip for width / height = aspect (OpenGL's projection).
  Eigen::Matrix4d projection(double aspect) const;
  /// Pixel position (x right, y down from the top-left corner, pixel centres at i + 0.5) of a world point in a
  /// width × height picture; nothing when the point is behind the camera.
  std::optional<Eigen::Vector2d> project(const Eigen::Vector3d& p, int width, int height) const;
  /// Unit direction from the eye through the pixel position (x, y), as in project().
  Eigen::Vector3d ray(double x, double y, int width, int height) const;
};

/// A camera looking down at the box's centre (40° above the horizontal, from the front right, `up` upward) from
/// just far enough that all of the box is in a picture of this aspect (5 % margin). Throws
/// InputError for an empty or unbounded box, a zero `up` or a non-positive aspect.
Camera frameBounds(const Aabb& box, const Eigen::Vector3d& up, double aspect);

}  // namespace unidist::render
