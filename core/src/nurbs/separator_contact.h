// The closest pair a separator (support_ball.h, support_tube.h) is fitted to. Internal.
#pragma once

#include "unidist/nurbs.h"

namespace unidist::nurbs {

/// Patch A at parameters xA (point pA) and patch B at xB (point pB), both points in A's frame; B's points map
/// there by X_AB.
struct SeparatorContact {
  const RationalBezierPatch& patchA;
  Eigen::Vector2d xA;
  const RationalBezierPatch& patchB;
  Eigen::Vector2d xB;
  Eigen::Isometry3d X_AB;
  Eigen::Vector3d pA, pB;
};

}  // namespace unidist::nurbs
