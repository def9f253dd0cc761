#include "pairs/analytic.h"

#include "convex/segments.h"
#include "pairs/convex_pair.h"
#include "unidist/primitives.h"

#include <cmath>
#include <limits>

namespace unidist::detail {

Eigen::Vector3d anyOrthogonal(const Eigen::Vector3d& v) {
  const Eigen::Vector3d axis = std::abs(v.x()) < 0.6 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return v.cross(axis).normalized();
}

double roundingSlack(double scale) { return 16 * std::numeric_limits<double>::epsilon() * scale; }

void markExact(DistanceResult& r, double scale) {
  const double slack = roundingSlack(scale + std::abs(r.distance));
  r.lowerBound = r.distance - slack;
  r.upperBound = r.distance + slack;
  r.status = Status::Certified;
}

double supportGapLowerBound(const PosedModel& a, const PosedModel& b, const Eigen::Vector3d& u) {
  const double maxA = u.dot(a.supportWorld(u));
  const double minB = u.dot(b.supportWorld(-u));
  const double gap = minB - maxA;
  // A NURBS support point is found by a search proved to 1e-13 × the model's size (unidist/nurbs.h).
  const auto searchSlack = [](const PosedModel& m) {
    return m.model.type() == ModelType::Nurbs ? 1e-13 * m.model.localBounds().diagonal() : 0.0;
  };
  return gap - roundingSlack(std::abs(maxA) + std::abs(minB)) - searchSlack(a) - searchSlack(b);
}

DistanceResult planeAny(const PosedModel& planeModel, const PosedModel& other, const QueryContext&) {
  const auto& plane = static_cast<const Plane&>(planeModel.model);
  const Eigen::Vector3d n_W = planeModel.dirToWorld(plane.normal());
  const double d_W = plane.offset() + n_W.dot(planeModel.X_WM.translation());
  const Eigen::Vector3d lowest_W = other.supportWorld(-n_W);
  const double s = n_W.dot(lowest_W) - d_W;

  DistanceResult r;
  r.distance = s;
  r.normal = n_W;  // out of the half-space, toward B; also the way B moves to separate
  r.pointB = lowest_W;
  r.pointA = lowest_W - s * n_W;
  r.iterations = 1;
  r.method = "plane-support";
  markExact(r, lowest_W.norm() + std::abs(d_W));
  return r;
}

DistanceResult sphereAny(const PosedModel& sphereModel, const PosedModel& other, const QueryContext& ctx,
                         bool& exact) {
  const double radius = static_cast<const Sphere&>(sphereModel.model).radius();
  const Eigen::Vector3d c_W = sphereModel.X_WM.translation();
  const SurfacePoint s = other.closestWorld(c_W);

  DistanceResult r;
  r.distance = s.signedDistance - radius;
  // The sphere leaves along the other model's inward normal at the closest point, whichever side c is on.
  r.normal = -s.normal;
  r.pointB = s.point;
  r.pointA = c_W + radius * r.normal;
  r.iterations = 1;
  r.method = "sphere-point-query";
  markExact(r, c_W.norm() + radius + std::abs(s.signedDistance));
  // The point query realises its distance; the true one may be up to its error nearer (a NURBS search's): a
  // centre outside may be that much nearer the surface, one inside that much less deep.
  if (s.signedDistance >= 0) r.lowerBound -= s.error;
  else r.upperBound += s.error;
  settleStatus(r, ctx.tolerance);
  // For a non-convex solid, depth of the centre only bounds the penetration (another part may block the exit).
  exact = r.distance >= 0 || convexSolid(other.model);
  return r;
}

std::optional<DistanceResult> sphereEscapeAlongNormal(const PosedModel& sphereModel, const PosedModel& other,
                                                      const QueryContext& ctx, const DistanceResult& sunk) {
  const double radius = static_cast<const Sphere&>(sphereModel.model).radius();
  const Eigen::Vector3d c_W = sphereModel.X_WM.translation();
  if (!(sunk.distance < 0) || !other.model.isSolid()) return std::nullopt;
  // The centre's nearest surface point lies inside the ball by −distance (realised: no translation shorter
  // keeps it out), so the depth is at least that; moved that far and a quarter tolerance more along the way the
  // sphere leaves (−normal: the contract's normal is the way the other model leaves), and proved clear by a
  // point query there, the sphere is out: the depth is at most that.
  const double depth = -sunk.upperBound;
  const double step = depth + 0.25 * ctx.tolerance;
  const SurfacePoint moved = other.closestWorld(c_W - step * sunk.normal);
  if (!(moved.signedDistance - moved.error >= radius)) return std::nullopt;  // blocked, or curved round the ball
  DistanceResult r = sunk;
  r.lowerBound = -step - roundingSlack(c_W.norm() + radius + step);
  r.method = "sphere-escape-along-normal";
  settleStatus(r, ctx.tolerance);
  return r;
}

DistanceResult capsuleCapsule(const PosedModel& a, const PosedModel& b, const QueryContext&) {
  const auto& ca = static_cast<const Capsule&>(a.model);
  const auto& cb = static_cast<const Capsule&>(b.model);
  const Eigen::Vector3d a0 = a.toWorld({0, 0, -ca.halfLength()}), a1 = a.toWorld({0, 0, ca.halfLength()});
  const Eigen::Vector3d b0 = b.toWorld({0, 0, -cb.halfLength()}), b1 = b.toWorld({0, 0, cb.halfLength()});
  const SegmentSegmentClosest sp = closestSegmentSegment(a0, a1, b0, b1);
  const Eigen::Vector3d between = sp.point2 - sp.point1;
  const double axisDistance = between.norm();

  DistanceResult r;
  // Crossing axes leave no direction in the points: any unit vector orthogonal to both axes separates fastest.
  if (axisDistance > roundingSlack(a0.norm() + b0.norm() + 1e-300)) {
    r.normal = between / axisDistance;
  } else {
    const Eigen::Vector3d n = (a1 - a0).cross(b1 - b0);
    r.normal = n.norm() > 0 ? n.normalized() : anyOrthogonal(a1 - a0);
  }
  r.distance = axisDistance - ca.radius() - cb.radius();
  r.pointA = sp.point1 + ca.radius() * r.normal;
  r.pointB = sp.point2 - cb.radius() * r.normal;
  r.iterations = 1;
  r.method = "capsule-segments";
  markExact(r, a0.norm() + a1.norm() + b0.norm() + b1.norm() + ca.radius() + cb.radius());
  return r;
}

}  // namespace unidist::detail
