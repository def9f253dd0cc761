// Torus about z: the points within r of the circle of radius R in the plane z = 0 (0 < r < R). In the
// half-plane (rho, z) that holds q the surface is the tube circle of radius r about (R, 0); the closest
// point lies in q's own half-plane because the tube stays at rho >= R - r > 0.
//
// Feature id: always 0. param = (theta = atan2(y, x), phi = angle about the tube from the outward
// direction toward +z), the parameters of the surface cells. Ties (primitives.h): on the z axis the tube
// point toward +x; on the centre circle the tube point at +z.
#include "unidist/primitives.h"

#include "primitives/cells.h"
#include "primitives/common.h"

namespace unidist {
namespace {

Eigen::Vector3d torusPoint(double R, double r, double theta, double phi) {
  const double rho = R + r * std::cos(phi);
  return {rho * std::cos(theta), rho * std::sin(theta), r * std::sin(phi)};
}

// In theta an arc of radius R + r·cos(phi) <= R + r·max cos; in phi an arc of the tube, radius r.
SurfaceCell torusCell(double R, double r, int face, double u0, double u1, double v0, double v1) {
  const double reach = prim::arcReach(R + r * prim::maxCos(v0, v1), u1 - u0) + prim::arcReach(r, v1 - v0);
  return prim::makeCell(face, u0, u1, v0, v1, torusPoint(R, r, 0.5 * (u0 + u1), 0.5 * (v0 + v1)), reach, R + r);
}

}  // namespace

Torus::Torus(double majorRadius, double tubeRadius) : R_(majorRadius), r_(tubeRadius) {
  prim::requirePositive("torus", "R", majorRadius);
  prim::requirePositive("torus", "r", tubeRadius);
  if (!(tubeRadius < majorRadius))
    throw InputError("torus: r must be < R (got R=" + prim::formatNumber(majorRadius) +
                     ", r=" + prim::formatNumber(tubeRadius) + ")");
}

Eigen::Vector3d Torus::circlePoint(double theta) const { return {R_ * std::cos(theta), R_ * std::sin(theta), 0.0}; }

SurfacePoint Torus::closestPoint(const Eigen::Vector3d& q) const {
  const double rho = std::hypot(q.x(), q.y());
  const Eigen::Vector2d u = prim::radialDirection(q.x(), q.y());
  const double dRho = rho - R_;
  const Eigen::Vector2d d = prim::unit2Or(dRho, q.z(), 0.0, 1.0);  // about the tube centre
  SurfacePoint s;
  const double pRho = R_ + r_ * d.x();
  s.point = Eigen::Vector3d(pRho * u.x(), pRho * u.y(), r_ * d.y());
  s.normal = Eigen::Vector3d(d.x() * u.x(), d.x() * u.y(), d.y());
  s.signedDistance = std::hypot(dRho, q.z()) - r_;
  s.feature = 0;
  s.param = {std::atan2(u.y(), u.x()), std::atan2(d.y(), d.x())};
  return s;
}

Aabb Torus::localBounds() const {
  Aabb b;
  b.min = Eigen::Vector3d(-R_ - r_, -R_ - r_, -r_);
  b.max = Eigen::Vector3d(R_ + r_, R_ + r_, r_);
  return b;
}

// One sqrt: the quartic form without it loses accuracy near the surface of a thin tube (its terms are
// of size R⁴ while the margin is of size R·r·distance).
bool Torus::inside(const Eigen::Vector3d& q) const {
  const double dRho = std::sqrt(q.x() * q.x() + q.y() * q.y()) - R_;
  return dRho * dRho + q.z() * q.z() < r_ * r_;
}

// Support of the hull: the centre circle's support plus r along dir.
Eigen::Vector3d Torus::support(const Eigen::Vector3d& dir) const {
  const Eigen::Vector2d u = prim::radialDirection(dir.x(), dir.y());
  return Eigen::Vector3d(R_ * u.x(), R_ * u.y(), 0.0) + r_ * prim::unitOr(dir, Eigen::Vector3d::UnitZ());
}

std::vector<SurfaceCell> Torus::surfaceCells() const {
  constexpr double kPi = 3.14159265358979323846;
  std::vector<SurfaceCell> cells;
  const auto make = [this](int f, double u0, double u1, double v0, double v1) {
    return torusCell(R_, r_, f, u0, u1, v0, v1);
  };
  for (int j = 0; j < 4; ++j) prim::quarterTurns(0, -kPi + 0.5 * kPi * j, -kPi + 0.5 * kPi * (j + 1), cells, make);
  return cells;
}

void Torus::splitCell(const SurfaceCell& cell, std::vector<SurfaceCell>& out) const {
  prim::splitInFour(cell, out, [this](int f, double u0, double u1, double v0, double v1) {
    return torusCell(R_, r_, f, u0, u1, v0, v1);
  });
}

std::string Torus::describe() const { return "torus R=" + prim::exact(R_) + " r=" + prim::exact(r_); }

}  // namespace unidist
