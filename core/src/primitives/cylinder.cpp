// Cylinder of radius r about z, z in [-h, h]. Worked in the half-plane (rho, z) that holds q, where the
// solid is the rectangle [0, r] x [-h, h]; rotating back about z is exact because the closest point of a
// surface of revolution lies in the query's own half-plane.
//
// Feature ids: 0 = side, 1 = top disc (z = +h), 2 = bottom disc (z = -h), 3 = top rim, 4 = bottom rim.
// Rims are reported only for points strictly outside both the side and a disc. A point inside or on the
// surface takes the nearest of side, top, bottom, ties in that order, so a point exactly on a rim answers
// as a side point with the side normal. On the axis the radial direction is +x (primitives.h).
// param: side and rims (angle atan2(y, x), z); discs (angle, rho) — the parameters of the surface cells.
#include "unidist/primitives.h"

#include "primitives/cells.h"
#include "primitives/common.h"

#include <algorithm>

namespace unidist {
namespace {

enum Feature { kSide = 0, kTop = 1, kBottom = 2, kTopRim = 3, kBottomRim = 4 };

Eigen::Vector3d cylinderPoint(double r, double h, int face, double u, double v) {
  if (face == kSide) return {r * std::cos(u), r * std::sin(u), v};
  return {v * std::cos(u), v * std::sin(u), face == kTop ? h : -h};
}

// Side: an arc of radius r in u, a line in v. Disc: an arc of radius at most v1 in u, a line in v.
SurfaceCell cylinderCell(double r, double h, int face, double u0, double u1, double v0, double v1) {
  const double reach = prim::arcReach(face == kSide ? r : v1, u1 - u0) + 0.5 * (v1 - v0);
  const Eigen::Vector3d mid = cylinderPoint(r, h, face, 0.5 * (u0 + u1), 0.5 * (v0 + v1));
  return prim::makeCell(face, u0, u1, v0, v1, mid, reach, r + h);
}

}  // namespace

Cylinder::Cylinder(double r, double halfHeight) : r_(r), h_(halfHeight) {
  prim::requirePositive("cylinder", "r", r);
  prim::requirePositive("cylinder", "h", halfHeight);
}

SurfacePoint Cylinder::closestPoint(const Eigen::Vector3d& q) const {
  const double rho = std::hypot(q.x(), q.y());
  const Eigen::Vector2d u = prim::radialDirection(q.x(), q.y());
  const double angle = std::atan2(u.y(), u.x());
  SurfacePoint s;

  if (rho > r_ || std::abs(q.z()) > h_) {
    const bool pastSide = rho > r_, pastCap = std::abs(q.z()) > h_;
    const double pz = std::clamp(q.z(), -h_, h_);
    // Within the disc the point keeps q's own x, y (no round trip through rho and u).
    s.point = pastSide ? Eigen::Vector3d(r_ * u.x(), r_ * u.y(), pz) : Eigen::Vector3d(q.x(), q.y(), pz);
    const double dRho = pastSide ? rho - r_ : 0.0, dZ = q.z() - pz;
    const Eigen::Vector2d d = prim::unit2Or(dRho, dZ, 0.0, 1.0);  // (0, 1) is never used: q is outside
    s.normal = Eigen::Vector3d(d.x() * u.x(), d.x() * u.y(), d.y());
    s.signedDistance = std::hypot(dRho, dZ);
    const bool top = q.z() > 0;
    s.feature = !pastCap ? kSide : (!pastSide ? (top ? kTop : kBottom) : (top ? kTopRim : kBottomRim));
    s.param = {angle, (s.feature == kTop || s.feature == kBottom) ? rho : pz};
    return s;
  }

  // Inside or on the surface: the nearest of side, top and bottom.
  const double toSide = r_ - rho, toTop = h_ - q.z(), toBottom = h_ + q.z();
  if (toSide <= toTop && toSide <= toBottom) {
    s.point = Eigen::Vector3d(r_ * u.x(), r_ * u.y(), q.z());
    s.normal = Eigen::Vector3d(u.x(), u.y(), 0);
    s.signedDistance = 0.0 - toSide;  // +0 on the surface
    s.feature = kSide;
    s.param = {angle, q.z()};
  } else {
    const bool top = toTop <= toBottom;
    s.point = Eigen::Vector3d(q.x(), q.y(), top ? h_ : -h_);
    s.normal = Eigen::Vector3d(0, 0, top ? 1 : -1);
    s.signedDistance = 0.0 - (top ? toTop : toBottom);
    s.feature = top ? kTop : kBottom;
    s.param = {angle, rho};
  }
  return s;
}

Aabb Cylinder::localBounds() const {
  Aabb b;
  b.min = Eigen::Vector3d(-r_, -r_, -h_);
  b.max = Eigen::Vector3d(r_, r_, h_);
  return b;
}

bool Cylinder::inside(const Eigen::Vector3d& q) const {
  return std::abs(q.z()) < h_ && q.x() * q.x() + q.y() * q.y() < r_ * r_;
}

Eigen::Vector3d Cylinder::support(const Eigen::Vector3d& dir) const {
  const Eigen::Vector2d u = prim::radialDirection(dir.x(), dir.y());
  return {r_ * u.x(), r_ * u.y(), dir.z() >= 0 ? h_ : -h_};
}

std::vector<SurfaceCell> Cylinder::surfaceCells() const {
  std::vector<SurfaceCell> cells;
  const auto make = [this](int f, double u0, double u1, double v0, double v1) {
    return cylinderCell(r_, h_, f, u0, u1, v0, v1);
  };
  prim::quarterTurns(kSide, -h_, h_, cells, make);
  prim::quarterTurns(kTop, 0.0, r_, cells, make);
  prim::quarterTurns(kBottom, 0.0, r_, cells, make);
  return cells;
}

void Cylinder::splitCell(const SurfaceCell& cell, std::vector<SurfaceCell>& out) const {
  prim::splitInFour(cell, out, [this](int f, double u0, double u1, double v0, double v1) {
    return cylinderCell(r_, h_, f, u0, u1, v0, v1);
  });
}

std::string Cylinder::describe() const { return "cylinder r=" + prim::exact(r_) + " h=" + prim::exact(h_); }

}  // namespace unidist
