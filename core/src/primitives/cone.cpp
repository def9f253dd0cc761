// Cone about z: base disc of radius r at z = -h, apex at z = +h. Worked in the half-plane (rho, z) that
// holds q, where the solid is the triangle apex A = (0, h), rim B = (r, -h), base centre C = (0, -h). The
// surface is the side AB and the base CB; the edge CA is the axis, inside the solid, so it is never a
// closest feature.
//  * Inside: both angles of the triangle at A and B are acute and the one at C is right, so the foot of the
//    perpendicular from an inside point onto line AB (and onto line CB) falls within that segment: the
//    distance is the smaller of the two line distances, ties to the side.
//  * Outside: the projection onto the (convex) triangle is unique and lies on AB or CB: the nearer of the
//    two clamped segment projections.
//
// Feature ids: 0 = side, 1 = base disc, 2 = rim, 3 = apex. Rim and apex are reported only for points
// outside; on the surface a point takes side before base, so the apex and the rim themselves answer with the
// side normal. On the axis the radial direction is +x (primitives.h).
// param: side (angle atan2(y, x), t = slant fraction from apex, 0..1); base (angle, rho); rim (angle, 1);
// apex (angle, 0) — the side and base parameters are those of the surface cells.
#include "unidist/primitives.h"

#include "primitives/cells.h"
#include "primitives/common.h"

#include <algorithm>

namespace unidist {
namespace {

enum Feature { kSide = 0, kBase = 1, kRim = 2, kApex = 3 };

Eigen::Vector3d conePoint(double r, double h, int face, double u, double v) {
  if (face == kSide) return {v * r * std::cos(u), v * r * std::sin(u), h - 2.0 * h * v};
  return {v * std::cos(u), v * std::sin(u), -h};
}

// Side: in u an arc of radius at most t1·r, in v a straight slant line of length L per unit t.
// Base: as the cylinder's discs.
SurfaceCell coneCell(double r, double h, int face, double u0, double u1, double v0, double v1) {
  const double reach = face == kSide ? prim::arcReach(v1 * r, u1 - u0) + 0.5 * std::hypot(r, 2.0 * h) * (v1 - v0)
                                     : prim::arcReach(v1, u1 - u0) + 0.5 * (v1 - v0);
  const Eigen::Vector3d mid = conePoint(r, h, face, 0.5 * (u0 + u1), 0.5 * (v0 + v1));
  return prim::makeCell(face, u0, u1, v0, v1, mid, reach, r + h);
}

}  // namespace

Cone::Cone(double r, double halfHeight) : r_(r), h_(halfHeight) {
  prim::requirePositive("cone", "r", r);
  prim::requirePositive("cone", "h", halfHeight);
}

SurfacePoint Cone::closestPoint(const Eigen::Vector3d& q) const {
  const double rho = std::hypot(q.x(), q.y()), z = q.z();
  const Eigen::Vector2d u = prim::radialDirection(q.x(), q.y());
  const double angle = std::atan2(u.y(), u.x());
  const double slant = std::hypot(r_, 2.0 * h_);
  const double nRho = 2.0 * h_ / slant, nZ = r_ / slant;  // outward unit normal of the side in (rho, z)
  const double toSideLine = rho * nRho + (z - h_) * nZ;   // signed: > 0 outside the side's line
  const double toBaseLine = -h_ - z;                      // signed: > 0 below the base
  const auto lift = [&](double pRho, double pZ) { return Eigen::Vector3d(pRho * u.x(), pRho * u.y(), pZ); };
  SurfacePoint s;

  if (toSideLine <= 0 && toBaseLine <= 0) {  // inside or on the surface
    if (toSideLine >= toBaseLine) {
      const double pRho = rho - toSideLine * nRho;
      s.point = lift(pRho, z - toSideLine * nZ);
      s.normal = lift(nRho, nZ);
      s.signedDistance = toSideLine;
      s.feature = kSide;
      s.param = {angle, std::clamp(pRho / r_, 0.0, 1.0)};
    } else {
      s.point = Eigen::Vector3d(q.x(), q.y(), -h_);
      s.normal = Eigen::Vector3d(0, 0, -1);
      s.signedDistance = toBaseLine;
      s.feature = kBase;
      s.param = {angle, rho};
    }
    return s;
  }

  // Outside. Side AB: t along A -> B = (r, -2h), clamped. Base CB: rho clamped to [0, r].
  const double t = std::clamp((rho * r_ - (z - h_) * 2.0 * h_) / (slant * slant), 0.0, 1.0);
  const double sideRho = t * r_, sideZ = h_ - 2.0 * h_ * t;
  const double sideDist = std::hypot(rho - sideRho, z - sideZ);
  const double baseRho = std::min(rho, r_);
  const double baseDist = std::hypot(rho - baseRho, z + h_);
  const bool onSide = sideDist <= baseDist;
  if (onSide && t > 0.0 && t < 1.0) {
    // The side's own region: its exact normal, as inside, rather than one rebuilt from a tiny difference.
    s.point = lift(rho - toSideLine * nRho, z - toSideLine * nZ);
    s.normal = lift(nRho, nZ);
    s.signedDistance = toSideLine;
    s.feature = kSide;
    s.param = {angle, t};
    return s;
  }
  const double pRho = onSide ? sideRho : baseRho, pZ = onSide ? sideZ : -h_;
  // Within the base the point keeps q's own x, y (no round trip through rho and u).
  s.point = (!onSide && rho <= r_) ? Eigen::Vector3d(q.x(), q.y(), -h_) : lift(pRho, pZ);
  // The fallbacks apply only when rounding put q on the surface: then the face normal.
  const Eigen::Vector2d d =
      onSide ? prim::unit2Or(rho - pRho, z - pZ, nRho, nZ) : prim::unit2Or(rho - pRho, z - pZ, 0, -1);
  s.normal = lift(d.x(), d.y());
  s.signedDistance = onSide ? sideDist : baseDist;
  if (s.signedDistance == 0.0) {
    // q is on the surface (rounding sent it here, not to the inside branch): a face, as documented.
    s.feature = onSide ? kSide : kBase;
    s.param = {angle, onSide ? t : baseRho};
  } else if (onSide) {
    s.feature = t <= 0.0 ? kApex : kRim;
    s.param = {angle, t};
  } else {
    s.feature = rho < r_ ? kBase : kRim;
    s.param = {angle, rho < r_ ? rho : 1.0};
  }
  return s;
}

Aabb Cone::localBounds() const {
  Aabb b;
  b.min = Eigen::Vector3d(-r_, -r_, -h_);
  b.max = Eigen::Vector3d(r_, r_, h_);
  return b;
}

// Strictly inside: above the base and within the side, rho < r (h - z) / (2h), squared (h - z > 0).
bool Cone::inside(const Eigen::Vector3d& q) const {
  const double above = h_ - q.z();
  if (!(q.z() > -h_ && above > 0)) return false;
  return 4.0 * h_ * h_ * (q.x() * q.x() + q.y() * q.y()) < r_ * r_ * above * above;
}

// The hull's extreme points are the apex and the rim circle; the best rim point lies along (dx, dy).
Eigen::Vector3d Cone::support(const Eigen::Vector3d& dir) const {
  const Eigen::Vector2d u = prim::radialDirection(dir.x(), dir.y());
  const double apexValue = dir.z() * h_;
  const double rimValue = r_ * std::hypot(dir.x(), dir.y()) - dir.z() * h_;
  if (apexValue >= rimValue) return {0, 0, h_};
  return {r_ * u.x(), r_ * u.y(), -h_};
}

std::vector<SurfaceCell> Cone::surfaceCells() const {
  std::vector<SurfaceCell> cells;
  const auto make = [this](int f, double u0, double u1, double v0, double v1) {
    return coneCell(r_, h_, f, u0, u1, v0, v1);
  };
  prim::quarterTurns(kSide, 0.0, 1.0, cells, make);
  prim::quarterTurns(kBase, 0.0, r_, cells, make);
  return cells;
}

void Cone::splitCell(const SurfaceCell& cell, std::vector<SurfaceCell>& out) const {
  prim::splitInFour(cell, out, [this](int f, double u0, double u1, double v0, double v1) {
    return coneCell(r_, h_, f, u0, u1, v0, v1);
  });
}

std::string Cone::describe() const { return "cone r=" + prim::exact(r_) + " h=" + prim::exact(h_); }

}  // namespace unidist
