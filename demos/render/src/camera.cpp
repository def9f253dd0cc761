#include "unidist/render/camera.h"

#include <cmath>

namespace unidist::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// The eye frame: x right, y up, z toward the viewer (OpenGL's convention), as rows of a rotation.
Eigen::Matrix3d eyeAxes(const Camera& c) {
  const Eigen::Vector3d back = (c.eye - c.target).normalized();
  Eigen::Vector3d right = c.up.cross(back);
  if (!(right.norm() > 1e-12)) right = back.unitOrthogonal();  // looking straight along `up`
  right.normalize();
  Eigen::Matrix3d R;
  R.row(0) = right.transpose();
  R.row(1) = back.cross(right).transpose();
  R.row(2) = back.transpose();
  return R;
}

}  // namespace

Eigen::Matrix4d Camera::view() const {
  const Eigen::Matrix3d R = eyeAxes(*this);
  Eigen::Matrix4d V = Eigen::Matrix4d::Identity();
  V.topLeftCorner<3, 3>() = R;
  V.topRightCorner<3, 1>() = -R * eye;
  return V;
}

Eigen::Matrix4d Camera::projection(double aspect) const {
  const double f = 1 / std::tan(fovY / 2), n = nearDistance, fa = farDistance;
  Eigen::Matrix4d P = Eigen::Matrix4d::Zero();
  P(0, 0) = f / aspect;
  P(1, 1) = f;
  P(2, 2) = (fa + n) / (n - fa);
  P(2, 3) = 2 * fa * n / (n - fa);
  P(3, 2) = -1;
  return P;
}

std::optional<Eigen::Vector2d> Camera::project(const Eigen::Vector3d& p, int width, int height) const {
  const Eigen::Vector4d clip = projection(double(width) / height) * view() * p.homogeneous();
  if (!(clip.w() > 0)) return std::nullopt;
  const Eigen::Vector2d ndc = clip.head<2>() / clip.w();
  return Eigen::Vector2d((ndc.x() + 1) / 2 * width, (1 - ndc.y()) / 2 * height);
}

Eigen::Vector3d Camera::ray(double x, double y, int width, int height) const {
  const double t = std::tan(fovY / 2), aspect = double(width) / height;
  const Eigen::Vector3d inEye((2 * x / width - 1) * t * aspect, (1 - 2 * y / height) * t, -1);
  return (eyeAxes(*this).transpose() * inEye).normalized();
}

Camera frameBounds(const Aabb& box, const Eigen::Vector3d& up, double aspect) {
  if (box.empty() || !box.bounded()) throw InputError("camera: the scene's bounds must be finite and not empty");
  if (!(up.norm() > 0) || !up.allFinite()) throw InputError("camera: the up direction must be a non-zero vector");
  if (!(aspect > 0) || !std::isfinite(aspect)) throw InputError("camera: the picture's aspect must be > 0");
  Camera c;
  c.up = up.normalized();
  // Horizontal axes: the world axis least along `up`, made horizontal, and its right-handed partner.
  Eigen::Index least = 0;
  c.up.cwiseAbs().minCoeff(&least);
  const Eigen::Vector3d e1 = (Eigen::Vector3d::Unit(least) - c.up[least] * c.up).normalized();
  const Eigen::Vector3d e2 = c.up.cross(e1);
  const double azimuth = -2 * kPi / 3, elevation = 40 * kPi / 180;
  const Eigen::Vector3d toEye =
      std::cos(elevation) * (std::cos(azimuth) * e1 + std::sin(azimuth) * e2) + std::sin(elevation) * c.up;
  c.target = box.center();
  c.eye = c.target + toEye;  // a unit step back fixes the eye axes; the distance follows
  const Eigen::Matrix3d axes = eyeAxes(c);
  // The nearest eye that sees all eight corners: a corner at (x, y) across and z toward the eye needs
  // distance − z >= |x| / tan(half width) and >= |y| / tan(half height).
  const double tanHalfHeight = std::tan(c.fovY / 2), tanHalfWidth = aspect * tanHalfHeight;
  const double radius = std::max(box.diagonal() / 2, 1e-9 * std::max(1.0, box.center().norm()));
  double distance = 0;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d p((corner & 1 ? box.max : box.min).x(), (corner & 2 ? box.max : box.min).y(),
                            (corner & 4 ? box.max : box.min).z());
    const Eigen::Vector3d e = axes * (p - c.target);
    distance = std::max({distance, e.z() + std::abs(e.x()) / tanHalfWidth, e.z() + std::abs(e.y()) / tanHalfHeight});
  }
  distance = std::max(1.05 * distance, 1.5 * radius);  // a margin; never inside the box's ball
  c.eye = c.target + distance * toEye;
  c.nearDistance = std::max(distance - 2 * radius, 0.01 * distance);
  c.farDistance = distance + 5 * radius;  // the floor's square reaches 3 radii from the centre
  return c;
}

}  // namespace unidist::render
