// Bullet's convex primitives as unidist primitives. Bullet keeps the margin of a box, cylinder, capsule, sphere
// and multi-sphere inside the size it reports (getHalfExtentsWithMargin, the radius), so those convert with
// outerMargin 0; a cone's margin is added outside its tip and rim (btConeShape::localGetSupportingVertex).
// Sizes read back from Bullet already include the local scaling (Bullet rescales them in setLocalScaling).
#include "shape_parts.h"

#include "unidist/primitives.h"

#include <algorithm>
#include <cmath>

namespace unidist::bullet {
namespace {

/// Rotation taking unidist's axis z to Bullet's axis `axis` (0, 1, 2): the cyclic permutation of the axes,
/// so it is proper.
Eigen::Isometry3d zAxisTo(int axis) {
  Eigen::Matrix3d R;
  R.col(0) = Eigen::Vector3d::Unit((axis + 1) % 3);
  R.col(1) = Eigen::Vector3d::Unit((axis + 2) % 3);
  R.col(2) = Eigen::Vector3d::Unit(axis);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = R;
  return X;
}

/// A rotation whose third column is the direction of d (d != 0).
Eigen::Matrix3d frameAlong(const Eigen::Vector3d& d) {
  Eigen::Matrix3d R;
  R.col(2) = d.normalized();
  int least = 0;  // the axis least aligned with d gives a well-conditioned perpendicular
  R.col(2).cwiseAbs().minCoeff(&least);
  R.col(0) = R.col(2).cross(Eigen::Vector3d::Unit(least)).normalized();
  R.col(1) = R.col(2).cross(R.col(0));
  return R;
}

/// Bullet keeps a shape of revolution circular whatever the scaling (it reads one radial extent); unidist
/// follows only when the two radial scales agree.
void requireRoundScaling(const btCollisionShape& s, int axis) {
  const btVector3& k = s.getLocalScaling();
  if (k[(axis + 1) % 3] != k[(axis + 2) % 3])
    throw shapeError(s, "local scaling " + formatVector(k) + " scales the two radial axes differently; Bullet keeps " +
                            "the cross-section circular, unidist will not guess which radius is meant");
}

void requireUniformScaling(const btCollisionShape& s) {
  const btVector3& k = s.getLocalScaling();
  if (k.x() != k.y() || k.y() != k.z())
    throw shapeError(s, "non-uniform local scaling " + formatVector(k) +
                            " would make an ellipsoid, which Bullet does not model (it keeps a sphere of the x scale)");
}

/// Radial extent of a cylinder with axis `axis` from its half extents (the component Bullet's getRadius reads).
double cylinderRadius(const btVector3& halfExtents, int axis) { return halfExtents[axis == 0 ? 1 : 0]; }

}  // namespace

ConvertedShape convertSphere(const btSphereShape& s) {
  requireUniformScaling(s);
  return {std::make_shared<Sphere>(double(s.getRadius())), 0, Eigen::Isometry3d::Identity()};
}

ConvertedShape convertBox(const btBoxShape& s) {
  return {std::make_shared<Box>(toEigen(s.getHalfExtentsWithMargin())), 0, Eigen::Isometry3d::Identity()};
}

ConvertedShape convertCapsule(const btCapsuleShape& s) {
  const int axis = s.getUpAxis();
  requireRoundScaling(s, axis);
  const double r = s.getRadius(), h = s.getHalfHeight();
  if (h == 0) return {std::make_shared<Sphere>(r), 0, Eigen::Isometry3d::Identity()};  // Bullet allows it; unidist's capsule needs h > 0
  return {std::make_shared<Capsule>(r, h), 0, zAxisTo(axis)};
}

ConvertedShape convertCylinder(const btCylinderShape& s) {
  const int axis = s.getUpAxis();
  const btVector3 h = s.getHalfExtentsWithMargin();  // scaled per axis: only the result must be round
  if (h[(axis + 1) % 3] != h[(axis + 2) % 3])
    throw shapeError(s, "half extents " + formatVector(h) + " give an elliptic cross-section; Bullet uses radius " +
                            std::to_string(cylinderRadius(h, axis)) + " only, so the shape is ambiguous");
  return {std::make_shared<Cylinder>(cylinderRadius(h, axis), double(h[axis])), 0, zAxisTo(axis)};
}

ConvertedShape convertCone(const btConeShape& s) {
  // Bullet's cone is centred on half its height (tip at +height/2 on its axis), as unidist's is.
  const int axis = s.getConeUpIndex();
  requireRoundScaling(s, axis);
  return {std::make_shared<Cone>(double(s.getRadius()), 0.5 * double(s.getHeight())), double(s.getMargin()),
          zAxisTo(axis)};
}

ConvertedShape convertMultiSphere(const btMultiSphereShape& s) {
  // The convex hull of the balls (margin inside, btMultiSphereShape.cpp): a ball, or a capsule for two equal
  // balls; more balls have no unidist counterpart.
  requireUniformScaling(s);
  const double k = s.getLocalScaling().x();
  const int n = s.getSphereCount();
  if (n < 1 || n > 2)
    throw shapeError(s, std::to_string(n) + " balls: only one ball or two equal balls (a capsule) are supported");
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d p0 = k * toEigen(s.getSpherePosition(0)), p1 = k * toEigen(s.getSpherePosition(n - 1));
  const double r0 = k * double(s.getSphereRadius(0)), r1 = k * double(s.getSphereRadius(n - 1));
  if (p0 == p1) {
    X.translation() = p0;
    return {std::make_shared<Sphere>(std::max(r0, r1)), 0, X};
  }
  if (r0 != r1)
    throw shapeError(s, "two balls of different radii (" + std::to_string(r0) + ", " + std::to_string(r1) +
                            ") make a tapered capsule, which unidist does not model");
  X.linear() = frameAlong(p1 - p0);
  X.translation() = 0.5 * (p0 + p1);
  return {std::make_shared<Capsule>(r0, 0.5 * (p1 - p0).norm()), 0, X};
}

ConvertedShape convertPlane(const btStaticPlaneShape& s) {
  // Bullet's plane is the half-space n·x <= constant (everything below is in contact), without margin.
  if (s.getLocalScaling() != btVector3(1, 1, 1))
    throw shapeError(s, "local scaling " + formatVector(s.getLocalScaling()) +
                            " is ignored by Bullet's plane collisions; set the plane's normal and constant instead");
  return {std::make_shared<Plane>(toEigen(s.getPlaneNormal()), double(s.getPlaneConstant())), 0,
          Eigen::Isometry3d::Identity()};
}

}  // namespace unidist::bullet
