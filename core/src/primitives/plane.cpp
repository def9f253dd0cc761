// Half-space n·x <= d (n unit after construction). Feature id: always 0. param: the closest point's
// coordinates in the tangent basis (t1, t2) of tangentBasis(), measured from the plane's point d·n.
// Unbounded: infinite AABB and bounding sphere, no surface cells, and a support map that is finite only
// along +n. The plane is never handed to GJK (plane pairs are analytic), so elsewhere support() returns a
// far point (1e300 away) instead of infinity, to keep arithmetic on it finite.
#include "unidist/primitives.h"

#include "primitives/common.h"

namespace unidist {
namespace {

constexpr double kFar = 1e300;

// A right-handed orthonormal (t1, t2) with t1 × t2 = n, built from the axis least aligned with n.
void tangentBasis(const Eigen::Vector3d& n, Eigen::Vector3d& t1, Eigen::Vector3d& t2) {
  Eigen::Index axis;
  n.cwiseAbs().minCoeff(&axis);
  t1 = n.cross(Eigen::Vector3d::Unit(axis)).normalized();
  t2 = n.cross(t1);
}

std::string vectorText(const Eigen::Vector3d& v) {
  return "(" + prim::formatNumber(v.x()) + ", " + prim::formatNumber(v.y()) + ", " + prim::formatNumber(v.z()) + ")";
}

}  // namespace

Plane::Plane(const Eigen::Vector3d& normal, double offset) {
  if (!normal.allFinite() || normal.isZero(0.0))
    throw InputError("plane: normal must be finite and non-zero (got " + vectorText(normal) + ")");
  if (!std::isfinite(offset)) throw InputError("plane: d must be finite (got " + prim::formatNumber(offset) + ")");
  // Divide by the largest component first so that |n| neither underflows nor overflows.
  const double m = normal.cwiseAbs().maxCoeff();
  const double length = (normal / m).norm();
  n_ = (normal / m) / length;
  d_ = (offset / m) / length;
  if (!std::isfinite(d_))
    throw InputError("plane: d / |n| must be finite (got d=" + prim::formatNumber(offset) +
                     ", n=" + vectorText(normal) + ")");
}

SurfacePoint Plane::closestPoint(const Eigen::Vector3d& q) const {
  const double height = n_.dot(q) - d_;
  SurfacePoint s;
  s.point = q - height * n_;
  s.normal = n_;
  s.signedDistance = height;
  s.feature = 0;
  Eigen::Vector3d t1, t2;
  tangentBasis(n_, t1, t2);
  s.param = {t1.dot(s.point), t2.dot(s.point)};  // the origin of the plane, d·n, is orthogonal to both
  return s;
}

Aabb Plane::localBounds() const {
  Aabb b;
  b.min = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());
  b.max = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  return b;
}

BoundingSphere Plane::localBoundingSphere() const {
  BoundingSphere s;
  s.center = d_ * n_;
  s.radius = std::numeric_limits<double>::infinity();
  return s;
}

bool Plane::inside(const Eigen::Vector3d& q) const { return n_.dot(q) < d_; }

// dir = λn + w (w ⟂ n): bounded only for w = 0 and λ >= 0, where every plane point is a support point.
// Otherwise the far point along w (or along -n when dir is -n) stands in for the point at infinity. A
// tangential part below a few ulps of |dir| is rounding, not a direction.
Eigen::Vector3d Plane::support(const Eigen::Vector3d& dir) const {
  const Eigen::Vector3d base = d_ * n_;
  const double along = n_.dot(dir);
  const Eigen::Vector3d tangential = dir - along * n_;
  if (prim::robustNorm(tangential) > 8.0 * std::numeric_limits<double>::epsilon() * prim::robustNorm(dir))
    return base + kFar * prim::unitOr(tangential, Eigen::Vector3d::Zero());
  if (along < 0) return base - kFar * n_;
  return base;
}

std::string Plane::describe() const {
  return "plane nx=" + prim::exact(n_.x()) + " ny=" + prim::exact(n_.y()) + " nz=" + prim::exact(n_.z()) +
         " d=" + prim::exact(d_);
}

}  // namespace unidist
