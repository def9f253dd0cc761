// A proved lower bound on the distance of two collision objects from their world bounding boxes: what lets a
// pair the broadphase hands over skip its query. Internal.
#pragma once

#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionShapes/btCollisionShape.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace unidist::bullet {

/// A proved lower bound on the distance between the two shapes: the largest gap between their world bounding boxes
/// along an axis (negative where the boxes overlap), less a pad for the rounding of the boxes to btScalar.
inline double aabbGap(const btCollisionObjectWrapper& a, const btCollisionObjectWrapper& b) {
  btVector3 minA, maxA, minB, maxB;
  a.getCollisionShape()->getAabb(a.getWorldTransform(), minA, maxA);
  b.getCollisionShape()->getAabb(b.getWorldTransform(), minB, maxB);
  double gap = -std::numeric_limits<double>::infinity(), scale = 1;
  for (int i = 0; i < 3; ++i) {
    gap = std::max({gap, double(minB[i]) - double(maxA[i]), double(minA[i]) - double(maxB[i])});
    scale = std::max({scale, std::abs(double(minA[i])), std::abs(double(maxA[i])), std::abs(double(minB[i])),
                      std::abs(double(maxB[i]))});
  }
  return gap - 1e-5 * scale;
}

}  // namespace unidist::bullet
