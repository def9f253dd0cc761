// massProperties(): picks the routine for the model's representation (mass_parts.h); principalInertia():
// the body frame engines want.
#include "unidist/mass.h"

#include "mass/mass_parts.h"
#include "mass/volume_moments.h"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <string>

namespace unidist {
namespace mass {

MassProperties toMassProperties(const VolumeMoments& m, const Model& model) {
  if (!(m.volume > 0) || !std::isfinite(m.volume))
    throw InputError("mass properties: " + model.describe() + " encloses no volume (computed " +
                     std::to_string(m.volume) + ")");
  MassProperties out;
  out.volume = m.volume;
  const Eigen::Vector3d offset = m.first / m.volume;  // centre of mass relative to the reference point
  out.centerOfMass = m.origin + offset;
  const Eigen::Matrix3d aboutCom = m.second - m.volume * offset * offset.transpose();
  out.inertia = inertiaFromCovariance(0.5 * (aboutCom + aboutCom.transpose()));
  return out;
}

MassProperties boundsBoxMass(const Model& m) {
  const Aabb b = m.localBounds();
  const Eigen::Vector3d size = b.max - b.min;
  if (b.empty() || !b.bounded() || !(size.prod() > 0))
    throw InputError("mass properties: " + m.describe() +
                     " has no inside and its bounding box, the stand-in solid, has no volume");
  MassProperties out;
  out.volume = size.prod();
  out.centerOfMass = b.center();
  const Eigen::Vector3d s2 = size.cwiseProduct(size);
  out.inertia = (out.volume / 12 * Eigen::Vector3d(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y())).asDiagonal();
  out.exact = false;
  return out;
}

}  // namespace mass

MassProperties massProperties(const Model& m) {
  MassProperties out;
  if (mass::primitiveMass(m, out)) return out;
  if (m.type() == ModelType::Plane)
    throw InputError("mass properties: " + m.describe() + " is unbounded (a half-space has no finite mass)");
  if (!m.isSolid()) return mass::boundsBoxMass(m);
  if (const auto* mesh = dynamic_cast<const TriangleMesh*>(&m)) return mass::meshMass(*mesh);
  if (const auto* nurbs = dynamic_cast<const NurbsModel*>(&m)) return mass::nurbsMass(*nurbs);
  throw InputError(std::string("mass properties: no mass routine for solid models of type ") + toString(m.type()));
}

PrincipalInertia principalInertia(const MassProperties& props, double mass) {
  if (!(mass > 0) || !std::isfinite(mass))
    throw InputError("principal inertia: the mass must be finite and > 0 (got " + std::to_string(mass) + ")");
  if (!(props.volume > 0) || !std::isfinite(props.volume))
    throw InputError("principal inertia: the volume must be finite and > 0 (got " + std::to_string(props.volume) + ")");
  const Eigen::Matrix3d scaled = (mass / props.volume) * 0.5 * (props.inertia + props.inertia.transpose());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scaled);
  if (eig.info() != Eigen::Success) throw InputError("principal inertia: the inertia tensor is not finite");
  Eigen::Matrix3d axes = eig.eigenvectors();
  if (axes.determinant() < 0) axes.col(2) = -axes.col(2);  // a proper rotation, not a reflection
  PrincipalInertia out;
  out.X_MB.linear() = axes;
  out.X_MB.translation() = props.centerOfMass;
  out.moments = eig.eigenvalues().cwiseMax(0.0);  // rounding can leave −ε for a flat body's smallest moment
  return out;
}

}  // namespace unidist
