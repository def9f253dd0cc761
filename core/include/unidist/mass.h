// Mass properties of a model for rigid-body simulation: volume, centre of mass and inertia tensor of the solid
// it bounds, for unit density. Exact for solids (analytic for primitives; divergence theorem over the triangles
// of a closed mesh; Gauss quadrature of the divergence theorem over the rational Bézier patches of a NURBS
// solid, accurate to rounding for the degrees CAD uses). A model without an inside (point cloud, open surface)
// has no volume: it gets the solid box of its bounds as a stand-in, and says so (exact = false).
#pragma once

#include "unidist/model.h"

namespace unidist {

struct MassProperties {
  double volume = 0;                                       ///< of the solid (or the stand-in), > 0
  Eigen::Vector3d centerOfMass = Eigen::Vector3d::Zero();  ///< model frame
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();       ///< about the centre of mass, model axes, density 1
  bool exact = true;                                       ///< false: the bounding-box stand-in was used
};

/// Throws InputError for an unbounded model (a half-space) or a degenerate one (zero volume).
MassProperties massProperties(const Model& m);

/// The body frame engines want: origin at the centre of mass, axes along the principal axes of inertia.
struct PrincipalInertia {
  Eigen::Isometry3d X_MB = Eigen::Isometry3d::Identity();  ///< body frame B in the model frame M (proper rotation)
  Eigen::Vector3d moments = Eigen::Vector3d::Zero();       ///< diagonal inertia in B for the given mass, >= 0
};

/// Scales props to `mass` (> 0) and diagonalises the inertia.
PrincipalInertia principalInertia(const MassProperties& props, double mass);

}  // namespace unidist
