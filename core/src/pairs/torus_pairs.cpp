#include "pairs/torus_pairs.h"

#include "generic/circle_search.h"
#include "pairs/analytic.h"
#include "unidist/primitives.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace unidist::detail {
namespace {

// Evaluation budgets of one angle search: ~1e5 point queries is a few milliseconds for primitives.
constexpr int kAngleBudget = 200000;
constexpr int kTraceBudget = 4000;    // a sphere-tracing step needs only a good sample, not a proof
constexpr int kVerifyBudget = 50000;  // proving a translation separates

/// The torus's centre circle in the world, seen against the other model moved by `shift` (world translation).
class SweptCircle {
 public:
  SweptCircle(const PosedModel& torus, const PosedModel& other)
      : torus_(torus), other_(other), shape_(static_cast<const Torus&>(torus.model)) {}

  double tube() const { return shape_.tubeRadius(); }
  double major() const { return shape_.majorRadius(); }

  Eigen::Vector3d point(double theta) const { return torus_.toWorld(shape_.circlePoint(theta)); }

  /// g(θ) = sd_other(C(θ) − shift): the tube overlaps the shifted model iff min g < tube().
  AngleFunction field(const Eigen::Vector3d& shift) const {
    return [this, shift](double theta, double halfWidth) {
      const double R = shape_.majorRadius();
      const Eigen::Vector3d q_W = point(theta) - shift;
      const SurfacePoint s = other_.closestWorld(q_W);
      const Eigen::Vector3d tangent = torus_.dirToWorld({-R * std::sin(theta), R * std::cos(theta), 0});
      return AngleSample{s.signedDistance, s.normal.dot(tangent), curvatureBound(q_W, halfWidth)};
    };
  }

  AngleMinimum search(const Eigen::Vector3d& shift, double tolerance, int budget = kAngleBudget) const {
    return minimizeOverAngle(field(shift), major(), tolerance, budget);
  }

  /// True (proved) when the torus and the other model moved by `shift` do not overlap.
  bool separatedAfter(const Eigen::Vector3d& shift) const {
    return provesAbove(field(shift), major(), tube(), kVerifyBudget);
  }

  const PosedModel& other() const { return other_; }

 private:
  /// g'' >= −bound on [θ − h, θ + h], or −1 when none is known. g'' = ∇sd·C'' + C'ᵀ H C' with |C''| = |C'| = R.
  /// A convex solid's signed distance is convex (H >= 0). A torus's is the distance to its circle, whose
  /// Hessian is >= −1/ρ (ρ: distance to that circle's axis), finite while the interval stays off the axis.
  double curvatureBound(const Eigen::Vector3d& q_W, double halfWidth) const {
    const double R = shape_.majorRadius();
    if (other_.model.isConvex()) return R;
    if (other_.model.type() != ModelType::Torus) return -1;
    const Eigen::Vector3d q = other_.toLocal(q_W);
    const double rhoMin = std::hypot(q.x(), q.y()) - R * halfWidth;
    return rhoMin > 0 ? R + R * R / rhoMin : -1;
  }

  const PosedModel& torus_;
  const PosedModel& other_;
  const Torus& shape_;
};

/// Fills points and normal from the circle point c and the other model's closest point to it (other moved by shift).
void witness(const SweptCircle& sweep, const Eigen::Vector3d& c, const Eigen::Vector3d& shift, DistanceResult& r) {
  const SurfacePoint s = sweep.other().closestWorld(c - shift);
  r.normal = -s.normal;
  r.pointA = c + sweep.tube() * r.normal;
  r.pointB = s.point;  // on the other model in its own (unshifted) place
}

/// A translation s·u (s >= start) found and proved to separate the torus from the other model, by sphere
/// tracing on the 1-Lipschitz overlap measure; +inf when the search gives up.
double exitAlong(const SweptCircle& sweep, const Eigen::Vector3d& u, double start, double tolerance, int& work) {
  double s = start;
  for (int step = 0; step < 300; ++step) {
    const AngleMinimum m = sweep.search(s * u, tolerance, kTraceBudget);
    work += m.evaluations;
    // m.value is a real sample, so tube − m.value never exceeds the true overlap: a safe step.
    const double overlap = sweep.tube() - m.value;
    if (overlap > 0) {
      s += std::max(overlap, 0.25 * tolerance);
      continue;
    }
    // Out by the best sample: prove it, allowing a growing margin where the contact is degenerate (a whole
    // arc touching at once needs many intervals to prove at a tight margin).
    for (double margin = 0.25 * tolerance; margin <= 1e4 * tolerance; margin *= 8) {
      if (sweep.separatedAfter((s + margin) * u)) return s + margin;
    }
    s += std::max(sweep.tube() - m.lowerBound, 1e4 * tolerance);
  }
  return std::numeric_limits<double>::infinity();
}

}  // namespace

DistanceResult torusSolid(const PosedModel& torus, const PosedModel& other, const QueryContext& ctx) {
  const SweptCircle sweep(torus, other);
  const double tol = ctx.tolerance;
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  const AngleMinimum m = sweep.search(zero, 0.5 * tol);

  DistanceResult r;
  r.iterations = m.evaluations;
  const Eigen::Vector3d c = sweep.point(m.theta);
  witness(sweep, c, zero, r);
  r.distance = m.value - sweep.tube();
  r.upperBound = r.distance;  // realised by the two witness points (or, overlapping, by the deepest ball)

  if (r.distance >= 0) {
    r.method = "torus-circle-search";
    // The angle search bounds the separation only when it also proves there is no overlap.
    const double hull = supportGapLowerBound(torus, other, r.normal);
    r.lowerBound = m.lowerBound >= sweep.tube() ? std::max(m.lowerBound - sweep.tube(), hull) : hull;
    r.lowerBound = std::min(r.lowerBound, r.distance);
    settleStatus(r, tol);
    return r;
  }

  // Penetrating. The deepest ball of the sweep alone needs a translation of −distance: a proved bound.
  r.method = "torus-escape-search";
  const double depthBound = -r.distance;
  const Eigen::Vector3d firstDirection = r.normal;
  double bestExit = std::numeric_limits<double>::infinity();
  Eigen::Vector3d bestDirection = firstDirection;
  int work = m.evaluations;

  auto tryDirection = [&](const Eigen::Vector3d& u, double start) {
    const double s = exitAlong(sweep, u, start, tol, work);
    if (s < bestExit) {
      bestExit = s;
      bestDirection = u;
    }
  };
  tryDirection(firstDirection, depthBound);
  if (bestExit > depthBound + tol) {
    // The deepest ball's way out is blocked by another part of the ring: search other directions, each
    // refined by following the contact normal where it comes out (a descent on the exit distance).
    const Eigen::Vector3d axis = torus.dirToWorld(Eigen::Vector3d::UnitZ());
    std::vector<Eigen::Vector3d> starts = {axis, -axis, -firstDirection};
    for (int i = 0; i < 3; ++i) {
      starts.push_back(Eigen::Vector3d::Unit(i));
      starts.push_back(-Eigen::Vector3d::Unit(i));
    }
    for (const Eigen::Vector3d& u0 : starts) {
      Eigen::Vector3d u = u0;
      for (int k = 0; k < 8; ++k) {
        const double s = exitAlong(sweep, u, 0, tol, work);
        if (!std::isfinite(s)) break;
        if (s < bestExit) {
          bestExit = s;
          bestDirection = u;
        }
        DistanceResult at;
        const AngleMinimum touch = sweep.search(s * u, tol, kTraceBudget);
        witness(sweep, sweep.point(touch.theta), s * u, at);
        if ((at.normal - u).norm() < 1e-12) break;
        u = at.normal;
      }
    }
  }

  r.iterations = work;
  r.upperBound = -depthBound;
  if (std::isfinite(bestExit)) {
    r.distance = -bestExit;
    r.lowerBound = -bestExit;
    r.normal = bestDirection;
    // Contact in the touching configuration, reported with B back at its place: pointB − pointA = distance·normal.
    const AngleMinimum touch = sweep.search(bestExit * bestDirection, tol, kTraceBudget);
    const Eigen::Vector3d touchPointOther = sweep.other().closestWorld(sweep.point(touch.theta) - bestExit * bestDirection).point;
    r.pointB = touchPointOther;
    r.pointA = touchPointOther + bestExit * bestDirection;
  } else {
    r.lowerBound = supportGapLowerBound(torus, other, r.normal);
  }
  r.lowerBound = std::min(r.lowerBound, r.distance);
  settleStatus(r, tol);
  return r;
}

}  // namespace unidist::detail
