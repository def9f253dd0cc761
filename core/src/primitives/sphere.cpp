// Sphere of radius r about the origin. Feature id: always 0. param = (longitude atan2(y, x) in [-π, π],
// latitude in [-π/2, π/2]), the same parameters as its surface cells.
#include "unidist/primitives.h"

#include "primitives/cells.h"
#include "primitives/common.h"

namespace unidist {
namespace {

constexpr double kPi = 3.14159265358979323846;

Eigen::Vector3d spherePoint(double r, double lon, double lat) {
  return r * Eigen::Vector3d(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat));
}

// Cells in (longitude, latitude). Moving in longitude follows a parallel of radius r·cos(lat), moving in
// latitude a meridian of radius r: both arcs, so the chord bounds of cells.h apply.
SurfaceCell sphereCell(double r, int face, double u0, double u1, double v0, double v1) {
  const double reach = prim::arcReach(r * prim::maxCos(v0, v1), u1 - u0) + prim::arcReach(r, v1 - v0);
  return prim::makeCell(face, u0, u1, v0, v1, spherePoint(r, 0.5 * (u0 + u1), 0.5 * (v0 + v1)), reach, r);
}

}  // namespace

Sphere::Sphere(double r) : r_(r) { prim::requirePositive("sphere", "r", r); }

SurfacePoint Sphere::closestPoint(const Eigen::Vector3d& q) const {
  // Every surface point is equally far from the centre: there the answer is (0, 0, r) (primitives.h).
  const Eigen::Vector3d n = prim::unitOr(q, Eigen::Vector3d::UnitZ());
  SurfacePoint s;
  s.point = r_ * n;
  s.normal = n;
  s.signedDistance = prim::robustNorm(q) - r_;
  s.feature = 0;
  s.param = {std::atan2(n.y(), n.x()), std::atan2(n.z(), std::hypot(n.x(), n.y()))};
  return s;
}

Aabb Sphere::localBounds() const {
  Aabb b;
  b.min = Eigen::Vector3d::Constant(-r_);
  b.max = Eigen::Vector3d::Constant(r_);
  return b;
}

bool Sphere::inside(const Eigen::Vector3d& q) const { return q.squaredNorm() < r_ * r_; }

Eigen::Vector3d Sphere::support(const Eigen::Vector3d& dir) const {
  return r_ * prim::unitOr(dir, Eigen::Vector3d::UnitZ());
}

std::vector<SurfaceCell> Sphere::surfaceCells() const {
  std::vector<SurfaceCell> cells;
  const auto make = [this](int f, double u0, double u1, double v0, double v1) {
    return sphereCell(r_, f, u0, u1, v0, v1);
  };
  prim::quarterTurns(0, -0.5 * kPi, 0.0, cells, make);
  prim::quarterTurns(0, 0.0, 0.5 * kPi, cells, make);
  return cells;
}

void Sphere::splitCell(const SurfaceCell& cell, std::vector<SurfaceCell>& out) const {
  prim::splitInFour(cell, out, [this](int f, double u0, double u1, double v0, double v1) {
    return sphereCell(r_, f, u0, u1, v0, v1);
  });
}

std::string Sphere::describe() const { return "sphere r=" + prim::exact(r_); }

}  // namespace unidist
