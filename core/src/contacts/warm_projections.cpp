#include "contacts/warm_projections.h"

#include "unidist/nurbs.h"

#include <cmath>

namespace unidist::contact {
namespace {

/// Whether q − p is normal to the surface at the local answer to ~1e-9 rad: Newton's own stop (a step moving the
/// point less than 1e-9 of the distance) can leave it short where the distance is flat — a probe far away, as
/// deepen()'s support probes are, near a pole where one parameter hardly moves the point — and an offset of
/// 1e-4 mm under a resting 150 mm ball is a lever that rolls it (0.05 mm in 20 s).
bool normalToSurface(const NurbsModel& m, const Eigen::Vector3d& q, const SurfacePoint& s) {
  const SurfaceDerivatives d = m.surfaces()[static_cast<std::size_t>(s.feature)].derivatives(s.param.x(), s.param.y());
  const Eigen::Vector3d r = q - d.point;
  const double slack = 1e-9 * r.norm() + 1e-13 * m.localBounds().diagonal();
  return std::abs(r.dot(d.du)) <= slack * d.du.norm() && std::abs(r.dot(d.dv)) <= slack * d.dv.norm() &&
         d.du.cross(d.dv).norm() > 0;
}

std::unique_ptr<tracking::LocalSurface> localFor(const Model& m) {
  return m.type() == ModelType::Nurbs ? tracking::LocalSurface::make(m) : nullptr;
}

}  // namespace

WarmProjections::WarmProjections(const Model& a, const Model& b) : a_(&a), b_(&b), la_(localFor(a)), lb_(localFor(b)) {}

SurfacePoint WarmProjections::project(const Model& m, const Eigen::Vector3d& q_M, int feature,
                                      const Eigen::Vector2d& param) {
  const tracking::LocalSurface* local = &m == a_ ? la_.get() : &m == b_ ? lb_.get() : nullptr;
  if (!local) return m.closestPoint(q_M);
  tracking::Hint hint{feature, param};
  const SurfacePoint s = local->project(q_M, hint, work_);
  if (normalToSurface(static_cast<const NurbsModel&>(m), q_M, s)) return s;
  ++work_.fallbacks;
  return m.closestPoint(q_M);
}

}  // namespace unidist::contact
