// Bullet ↔ Eigen values (btScalar may be float or double). Internal.
#pragma once

#include <LinearMath/btTransform.h>
#include <Eigen/Geometry>

namespace unidist::bullet {

inline Eigen::Vector3d toEigen(const btVector3& v) { return {double(v.x()), double(v.y()), double(v.z())}; }
inline btVector3 toBullet(const Eigen::Vector3d& v) { return btVector3(btScalar(v.x()), btScalar(v.y()), btScalar(v.z())); }

inline Eigen::Isometry3d toEigen(const btTransform& t) {
  // Through the quaternion, renormalised in double: a float build's basis is orthonormal to ~1e-7 only, and the
  // core inverts poses by transposing.
  const btQuaternion q = t.getRotation();
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::Quaterniond(double(q.w()), double(q.x()), double(q.y()), double(q.z())).normalized().toRotationMatrix();
  X.translation() = toEigen(t.getOrigin());
  return X;
}

inline btTransform toBullet(const Eigen::Isometry3d& X) {
  const Eigen::Matrix3d& R = X.linear();
  btMatrix3x3 basis(btScalar(R(0, 0)), btScalar(R(0, 1)), btScalar(R(0, 2)), btScalar(R(1, 0)), btScalar(R(1, 1)),
                    btScalar(R(1, 2)), btScalar(R(2, 0)), btScalar(R(2, 1)), btScalar(R(2, 2)));
  return btTransform(basis, toBullet(Eigen::Vector3d(X.translation())));
}

}  // namespace unidist::bullet
