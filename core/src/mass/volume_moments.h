// Volume integrals of a solid about a reference point, the common currency of the mesh and NURBS routines:
// integrating about a point near the solid (the centre of its bounds) rather than the model origin keeps
// the second moments free of cancellation for a part far from its origin.
#pragma once

#include "unidist/mass.h"

namespace unidist::mass {

struct VolumeMoments {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< reference point c (model frame)
  double volume = 0;                                 ///< ∫ dV
  Eigen::Vector3d first = Eigen::Vector3d::Zero();   ///< ∫ (x − c) dV
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();  ///< ∫ (x − c)(x − c)ᵀ dV
};

/// Volume, centre of mass and inertia about it (density 1); throws InputError naming `model` when the
/// volume is not positive (a flat or inside-out solid).
MassProperties toMassProperties(const VolumeMoments& m, const Model& model);

/// Inertia tensor of a body from its second moments about its centre of mass: tr(C)·1 − C.
inline Eigen::Matrix3d inertiaFromCovariance(const Eigen::Matrix3d& C) {
  return C.trace() * Eigen::Matrix3d::Identity() - C;
}

}  // namespace unidist::mass
