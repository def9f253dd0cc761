// Ray casting by sphere tracing on the unsigned distance (unidist/raycast.h).
#include "unidist/raycast.h"

#include <algorithm>
#include <cmath>

namespace unidist {
namespace {

void checkInputs(const Eigen::Isometry3d& X_WM, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                 double maxLength, double tolerance) {
  if (!X_WM.matrix().allFinite()) throw InputError("raycast: non-finite pose");
  if (!origin.allFinite()) throw InputError("raycast: non-finite ray origin");
  if (!dir.allFinite() || std::abs(dir.norm() - 1) > 1e-6) throw InputError("raycast: direction must be a unit vector");
  if (!std::isfinite(maxLength) || maxLength < 0) throw InputError("raycast: maxLength must be finite and >= 0");
  if (!std::isfinite(tolerance) || tolerance <= 0) throw InputError("raycast: tolerance must be finite and > 0");
}

/// The part [t0, t1] of the ray o + t·d, 0 <= t <= maxLength, inside box (slab test); false when it misses.
bool clipToBox(const Aabb& box, const Eigen::Vector3d& o, const Eigen::Vector3d& d, double maxLength, double& t0,
               double& t1) {
  t0 = 0;
  t1 = maxLength;
  for (int i = 0; i < 3; ++i) {
    if (d[i] == 0) {
      if (o[i] < box.min[i] || o[i] > box.max[i]) return false;
      continue;
    }
    double a = (box.min[i] - o[i]) / d[i], b = (box.max[i] - o[i]) / d[i];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  return t0 <= t1;
}

/// Newton steps on the signed distance along the ray, for solids: the sphere-traced t is within the tolerance of
/// the surface; this brings a transversal hit onto it. A step is kept only when it is small (this root, not
/// another one) and improves the distance.
double refineOnSolid(const Model& m, const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t, double maxLength,
                     double tolerance) {
  SurfacePoint s = m.closestPoint(o + t * d);
  for (int i = 0; i < 8 && s.signedDistance != 0; ++i) {
    const double slope = d.dot(s.normal);  // d(signed distance)/dt near the surface
    if (std::abs(slope) < 1e-3) break;     // tangent: the traced point is as good as it gets
    const double tNew = t - s.signedDistance / slope;
    if (std::abs(tNew - t) > 4 * tolerance / std::abs(slope) || tNew < 0 || tNew > maxLength) break;
    const SurfacePoint sNew = m.closestPoint(o + tNew * d);
    if (std::abs(sNew.signedDistance) >= std::abs(s.signedDistance)) break;
    t = tNew;
    s = sNew;
  }
  return t;
}

}  // namespace

RayHit raycast(const Model& m, const Eigen::Isometry3d& X_WM, const Eigen::Vector3d& origin_W,
               const Eigen::Vector3d& dir_W, double maxLength, double tolerance) {
  checkInputs(X_WM, origin_W, dir_W, maxLength, tolerance);
  RayHit out;
  const Eigen::Isometry3d X_MW = X_WM.inverse();
  const Eigen::Vector3d o = X_MW * origin_W;
  const Eigen::Vector3d d = (X_MW.linear() * dir_W).normalized();

  double t0 = 0, t1 = maxLength;
  Aabb box = m.localBounds();
  if (box.bounded()) {
    box.min.array() -= tolerance;
    box.max.array() += tolerance;
    if (!clipToBox(box, o, d, maxLength, t0, t1)) return out;
  }
  out.startedInside = m.isSolid() && m.inside(o);

  double t = t0;
  for (int step = 0; step < kMaxRaySteps; ++step) {
    const SurfacePoint s = m.closestPoint(o + t * d);
    const double gap = std::abs(s.signedDistance);
    if (gap <= tolerance) {
      if (m.isSolid()) t = refineOnSolid(m, o, d, t, maxLength, tolerance);
      const Eigen::Vector3d q = o + t * d;
      const SurfacePoint at = m.closestPoint(q);
      // A point has no surface normal of its own: the ray is reflected straight back.
      Eigen::Vector3d n = m.type() == ModelType::PointCloud ? Eigen::Vector3d(-d) : at.normal;
      if (n.dot(d) > 0) n = -n;  // the side the ray comes from
      out.hit = true;
      out.t = t;
      out.point = X_WM * q;
      out.normal = X_WM.linear() * n;
      out.feature = at.feature;
      return out;
    }
    t += std::max(gap, tolerance);
    if (t > t1) return out;
  }
  out.exhausted = true;
  return out;
}

}  // namespace unidist
