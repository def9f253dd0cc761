// Capsule: the segment (0,0,-h)..(0,0,+h) swept by a ball of radius r. The closest point is the segment's
// closest point pushed out by r along the way to q.
//
// Feature ids: 0 = cylindrical band (|z| <= h), 1 = top hemisphere (z > h), 2 = bottom hemisphere (z < -h).
// param: band (angle atan2(y, x), z); hemispheres (angle, latitude about the cap centre, in [0, π/2] on top
// and [-π/2, 0] below) — the parameters of the surface cells. On the segment itself the radial direction
// is +x (primitives.h).
#include "unidist/primitives.h"

#include "primitives/cells.h"
#include "primitives/common.h"

#include <algorithm>

namespace unidist {
namespace {

constexpr double kPi = 3.14159265358979323846;
enum Face { kBand = 0, kTop = 1, kBottom = 2 };

Eigen::Vector3d capsulePoint(double r, double h, int face, double u, double v) {
  if (face == kBand) return {r * std::cos(u), r * std::sin(u), v};
  const double zc = face == kTop ? h : -h;
  return {r * std::cos(v) * std::cos(u), r * std::cos(v) * std::sin(u), zc + r * std::sin(v)};
}

// Band: an arc of radius r in u, a straight line in v. Hemispheres: as the sphere's cells.
SurfaceCell capsuleCell(double r, double h, int face, double u0, double u1, double v0, double v1) {
  const double reach = face == kBand ? prim::arcReach(r, u1 - u0) + 0.5 * (v1 - v0)
                                     : prim::arcReach(r * prim::maxCos(v0, v1), u1 - u0) + prim::arcReach(r, v1 - v0);
  const Eigen::Vector3d mid = capsulePoint(r, h, face, 0.5 * (u0 + u1), 0.5 * (v0 + v1));
  return prim::makeCell(face, u0, u1, v0, v1, mid, reach, r + h);
}

}  // namespace

Capsule::Capsule(double r, double halfLength) : r_(r), h_(halfLength) {
  prim::requirePositive("capsule", "r", r);
  prim::requirePositive("capsule", "h", halfLength);
}

SurfacePoint Capsule::closestPoint(const Eigen::Vector3d& q) const {
  const double zc = std::clamp(q.z(), -h_, h_);
  const Eigen::Vector3d away(q.x(), q.y(), q.z() - zc);  // from the segment's closest point to q
  const Eigen::Vector3d n = prim::unitOr(away, Eigen::Vector3d::UnitX());
  SurfacePoint s;
  s.point = Eigen::Vector3d(0, 0, zc) + r_ * n;
  s.normal = n;
  s.signedDistance = prim::robustNorm(away) - r_;
  s.feature = q.z() > h_ ? kTop : (q.z() < -h_ ? kBottom : kBand);
  const double angle = std::atan2(n.y(), n.x());
  s.param = {angle, s.feature == kBand ? zc : std::atan2(n.z(), std::hypot(n.x(), n.y()))};
  return s;
}

Aabb Capsule::localBounds() const {
  Aabb b;
  b.min = Eigen::Vector3d(-r_, -r_, -h_ - r_);
  b.max = Eigen::Vector3d(r_, r_, h_ + r_);
  return b;
}

bool Capsule::inside(const Eigen::Vector3d& q) const {
  const double dz = q.z() - std::clamp(q.z(), -h_, h_);
  return q.x() * q.x() + q.y() * q.y() + dz * dz < r_ * r_;
}

Eigen::Vector3d Capsule::support(const Eigen::Vector3d& dir) const {
  const Eigen::Vector3d end(0, 0, dir.z() >= 0 ? h_ : -h_);
  return end + r_ * prim::unitOr(dir, Eigen::Vector3d::UnitZ());
}

std::vector<SurfaceCell> Capsule::surfaceCells() const {
  std::vector<SurfaceCell> cells;
  const auto make = [this](int f, double u0, double u1, double v0, double v1) {
    return capsuleCell(r_, h_, f, u0, u1, v0, v1);
  };
  prim::quarterTurns(kBand, -h_, h_, cells, make);
  prim::quarterTurns(kTop, 0.0, 0.5 * kPi, cells, make);
  prim::quarterTurns(kBottom, -0.5 * kPi, 0.0, cells, make);
  return cells;
}

void Capsule::splitCell(const SurfaceCell& cell, std::vector<SurfaceCell>& out) const {
  prim::splitInFour(cell, out, [this](int f, double u0, double u1, double v0, double v1) {
    return capsuleCell(r_, h_, f, u0, u1, v0, v1);
  });
}

std::string Capsule::describe() const { return "capsule r=" + prim::exact(r_) + " h=" + prim::exact(h_); }

}  // namespace unidist
