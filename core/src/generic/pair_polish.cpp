#include "generic/pair_polish.h"

#include "tracking/local_surface.h"
#include "unidist/nurbs.h"

#include <algorithm>

#include <cmath>
#include <limits>

namespace unidist::detail {
namespace {

constexpr int kMaxPolishSteps = 64;
// Relative to the model's size: the rounding of the searches' bounds (256 ulps of the coordinates on each side,
// and the certified values' own allowances).
constexpr double kSettledWidth = 2e-13;

/// The parameters of the control point nearest to p_M (Greville abscissae): where Newton starts to find the
/// parameters of a point on the surface.
tracking::Hint nodalHint(const NurbsModel& m, const Eigen::Vector3d& p_M) {
  const auto greville = [](const std::vector<double>& knots, int degree, int i, double lo, double hi) {
    double sum = 0;
    for (int k = 1; k <= degree; ++k) sum += knots[static_cast<std::size_t>(i + k)];
    return std::clamp(sum / degree, lo, hi);
  };
  tracking::Hint best;
  double nearest = std::numeric_limits<double>::infinity();
  for (int s = 0; s < static_cast<int>(m.surfaces().size()); ++s) {
    const NurbsSurface& S = m.surfaces()[static_cast<std::size_t>(s)];
    for (int i = 0; i < S.countU(); ++i)
      for (int j = 0; j < S.countV(); ++j) {
        const double d = (S.controlPoint(i, j).head<3>() - p_M).squaredNorm();
        if (d < nearest) {
          nearest = d;
          best.feature = s;
          best.param = {greville(S.knotsU(), S.degreeU(), i, S.uMin(), S.uMax()),
                        greville(S.knotsV(), S.degreeV(), j, S.vMin(), S.vMax())};
        }
      }
  }
  return best;
}

/// A model's projection for the polish: local (Newton) on a NURBS model from the parameters of the answer's own
/// point, the exact query on every other model (and where Newton cannot find the answer's point).
struct Projector {
  const PosedModel& posed;
  std::unique_ptr<tracking::LocalSurface> local;  // NURBS only
  tracking::Hint hint;

  Projector(const PosedModel& p, const Eigen::Vector3d& start_W) : posed(p) {
    const auto* nurbs = dynamic_cast<const NurbsModel*>(&p.model);
    if (!nurbs) return;
    local = tracking::LocalSurface::make(p.model);
    const Eigen::Vector3d start = p.toLocal(start_W);
    hint = nodalHint(*nurbs, start);
    tracking::Work work;
    const SurfacePoint s = local->project(start, hint, work);  // the start is on the surface: its own parameters
    if (!((s.point - start).norm() <= 1e-9 * p.model.localBounds().diagonal())) hint = local->hintOf(p.model.closestPoint(start));
  }

  Eigen::Vector3d project(const Eigen::Vector3d& q_W) {
    const Eigen::Vector3d q = posed.toLocal(q_W);
    if (!local) return posed.toWorld(posed.model.closestPoint(q).point);
    tracking::Work work;
    return posed.toWorld(local->project(q, hint, work).point);
  }
};

/// Both NURBS solids: their answers come polished from their own routine, and polishSeparation leaves them.
bool nurbsSolids(const PosedModel& a, const PosedModel& b) {
  return a.model.type() == ModelType::Nurbs && a.model.isSolid() && b.model.type() == ModelType::Nurbs &&
         b.model.isSolid();
}

}  // namespace

void polishAcrossPatches(const PosedModel& a, const PosedModel& b, DistanceResult& r, double tolerance,
                         double enough) {
  if (!(r.lowerBound > 0) || !(r.distance > 0)) return;
  if (a.model.type() != ModelType::Nurbs && b.model.type() != ModelType::Nurbs) return;
  // Bounds already within rounding of each other (2e-13 of the NURBS model's size): the polish could not move the
  // distance by more, and its projections cost as much as a small search.
  double size = 0;
  for (const PosedModel* m : {&a, &b})
    if (m->model.type() == ModelType::Nurbs) size = std::max(size, m->model.localBounds().diagonal());
  if (r.upperBound - r.lowerBound <= kSettledWidth * size) return;
  Projector pa(a, r.pointA), pb(b, r.pointB);
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
    if (shrink <= std::max(enough, 4 * std::numeric_limits<double>::epsilon() * (1 + pointB.cwiseAbs().maxCoeff())))
      break;
  }
  r.upperBound = std::min(r.upperBound, r.distance);
  settleStatus(r, tolerance);
}

void polishSeparation(const PosedModel& a, const PosedModel& b, DistanceResult& r, double tolerance) {
  // Two NURBS solids meet in the NURBS–NURBS search (dispatch.cpp), whose best pair is a pair-Newton end: a
  // stationary point already, unless it lies on a patch edge, where that routine polishes it itself.
  if (!nurbsSolids(a, b)) polishAcrossPatches(a, b, r, tolerance);
}

}  // namespace unidist::detail
