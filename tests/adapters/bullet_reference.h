// Bullet's own answer for a convex pair, the reference the Bullet adapter and plugin tests compare against.
#pragma once

#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btPointCollector.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>
#include <btBulletCollisionCommon.h>

#include <limits>

namespace bullet_reference {

/// Bullet's closest distance for a convex pair: its GJK (with EPA for overlaps) on the shapes' support maps and
/// margins. The simplex solver's equal-vertex threshold (1e-4, squared) is lowered: with it GJK stops up to
/// ~1e-3 early on curved shapes (cylinder, cone), which would hide the differences this test looks for.
inline double bulletConvexDistance(const btConvexShape& a, const btTransform& X_WA, const btConvexShape& b,
                            const btTransform& X_WB) {
  btVoronoiSimplexSolver simplex;
  simplex.setEqualVertexThreshold(0);
  btGjkEpaPenetrationDepthSolver epa;
  btGjkPairDetector gjk(&a, &b, &simplex, &epa);
  btGjkPairDetector::ClosestPointInput input;
  input.m_transformA = X_WA;
  input.m_transformB = X_WB;
  btPointCollector result;
  gjk.getClosestPoints(input, result, nullptr);
  return result.m_hasResult ? double(result.m_distance) : std::numeric_limits<double>::infinity();
}

}  // namespace bullet_reference
