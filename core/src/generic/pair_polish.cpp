#include "generic/pair_polish.h"

#include "tracking/local_surface.h"

#include <cmath>
#include <limits>

namespace unidist::detail {
namespace {

constexpr int kMaxPolishSteps = 64;

/// A model's projection for the polish: the exact global query first (it also gives the hint), then local.
struct Projector {
  const PosedModel& posed;
  std::unique_ptr<tracking::LocalSurface> local;  // NURBS only: Newton from the hint
  tracking::Hint hint;
  bool started = false;

  explicit Projector(const PosedModel& p) : posed(p) {
    if (p.model.type() == ModelType::Nurbs) local = tracking::LocalSurface::make(p.model);
  }

  Eigen::Vector3d project(const Eigen::Vector3d& q_W) {
    const Eigen::Vector3d q = posed.toLocal(q_W);
    if (!local || !started) {
      const SurfacePoint s = posed.model.closestPoint(q);
      if (local) hint = local->hintOf(s);
      started = true;
      return posed.toWorld(s.point);
    }
    tracking::Work work;
    return posed.toWorld(local->project(q, hint, work).point);
  }
};

}  // namespace

void polishSeparation(const PosedModel& a, const PosedModel& b, DistanceResult& r, double tolerance) {
  if (!(r.lowerBound > 0) || !(r.distance > 0)) return;
  if (a.model.type() != ModelType::Nurbs && b.model.type() != ModelType::Nurbs) return;
  Projector pa(a), pb(b);
  Eigen::Vector3d pointA = r.pointA;
  double best = r.distance;
  for (int step = 0; step < kMaxPolishSteps; ++step) {
    const Eigen::Vector3d pointB = pb.project(pointA);
    const Eigen::Vector3d nextA = pa.project(pointB);
    const double gap = (pointB - nextA).norm();
    if (!(gap < best)) break;  // no longer shrinking: at the local minimum, to rounding
    const double shrink = best - gap;
    best = gap;
    pointA = nextA;
    r.pointA = nextA;
    r.pointB = pointB;
    r.distance = gap;
    if (gap > 0) r.normal = (pointB - nextA) / gap;
    if (shrink <= 4 * std::numeric_limits<double>::epsilon() * (1 + pointB.cwiseAbs().maxCoeff())) break;
  }
  r.upperBound = std::min(r.upperBound, r.distance);
  settleStatus(r, tolerance);
}

}  // namespace unidist::detail
