#include "generic/ball_union.h"

#include "nurbs/objectives.h"
#include "nurbs/patch_search.h"
#include "unidist/nurbs.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace unidist::detail {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr int kMaxBalls = 24;         // balls kept for the union (its triple points cost the cube of this)
constexpr int kStartsPerSide = 3;     // a patch's nearest points are polished from this many starts squared
constexpr double kDistinct = 1e-6;    // of the radius: surface points nearer each other than this are one
constexpr double kShallowShare = 0.25;  // points less deep than this share of the deepest are not kept
constexpr int kGilbertSteps = 200;  // steps towards the nearest point of the active normals' hull
constexpr double kActive = 1e-9;  // of the radius: a sphere this near the union's nearest outside point passes it

/// The nearest point to the origin of the circle where the spheres (u, r) and (v, r) meet; none where they do not.
bool circleNearest(const Eigen::Vector3d& u, const Eigen::Vector3d& v, double r, Eigen::Vector3d& t) {
  const Eigen::Vector3d d = v - u;
  const double length = d.norm();
  if (!(length > 0) || length >= 2 * r) return false;
  const Eigen::Vector3d n = d / length, m = 0.5 * (u + v);
  const double circle = std::sqrt(r * r - 0.25 * length * length);
  Eigen::Vector3d w = n * n.dot(m) - m;  // from the circle's centre to the origin's projection on its plane
  if (!(w.norm() > 1e-12 * r)) w = n.unitOrthogonal();
  t = m + circle * w.normalized();
  return true;
}

/// The two points where the spheres (u, r), (v, r) and (w, r) meet; none where they do not.
bool triplePoints(const Eigen::Vector3d& u, const Eigen::Vector3d& v, const Eigen::Vector3d& w, double r,
                  Eigen::Vector3d& t0, Eigen::Vector3d& t1) {
  const Eigen::Vector3d a = v - u, b = w - u, n = a.cross(b);
  const double n2 = n.squaredNorm();
  if (!(n2 > 1e-24 * a.squaredNorm() * b.squaredNorm())) return false;  // collinear centres
  // The triangle's circumcentre (relative to u), then along its normal to the spheres.
  const Eigen::Vector3d centre = (a.squaredNorm() * b.cross(n) + b.squaredNorm() * n.cross(a)) / (2 * n2);
  const double h2 = r * r - centre.squaredNorm();
  if (!(h2 >= 0)) return false;
  const Eigen::Vector3d up = std::sqrt(h2 / n2) * n;
  t0 = u + centre + up;
  t1 = u + centre - up;
  return true;
}

/// A unit direction d with d·n > 0 for every unit normal n given: the nearest point of their convex hull to the
/// origin (Gilbert's iteration), normalised; zero where the hull holds the origin (no such direction).
Eigen::Vector3d offEvery(const std::vector<Eigen::Vector3d>& normals) {
  if (normals.empty()) return Eigen::Vector3d::Zero();
  Eigen::Vector3d x = normals.front();
  for (int it = 0; it < kGilbertSteps; ++it) {
    const auto lowest = std::min_element(normals.begin(), normals.end(), [&](const Eigen::Vector3d& p,
                                                                             const Eigen::Vector3d& q) {
      return x.dot(p) < x.dot(q);
    });
    const Eigen::Vector3d d = *lowest - x;
    if (x.squaredNorm() - x.dot(*lowest) <= 1e-15 || !(d.squaredNorm() > 0)) break;
    x += std::clamp(-x.dot(d) / d.squaredNorm(), 0.0, 1.0) * d;
  }
  const bool off = x.norm() > 1e-9 && std::all_of(normals.begin(), normals.end(), [&](const Eigen::Vector3d& n) {
    return x.dot(n) > 0;
  });
  return off ? Eigen::Vector3d(x.normalized()) : Eigen::Vector3d::Zero();
}

/// The balls worth the union: distinct, the deepest first, then each farthest from those kept (the contacts
/// all round a ring's hole, not the ones crowded at one seam). Balls holding the origin by less than a share of
/// the deepest are left out, and so are those not holding it unless within `reach` of it (the contacts a way
/// out of length `reach` would make).
std::vector<Eigen::Vector3d> spreadDeepest(std::vector<Eigen::Vector3d> centres, double radius, double reach) {
  std::sort(centres.begin(), centres.end(),
            [](const Eigen::Vector3d& x, const Eigen::Vector3d& y) { return x.squaredNorm() < y.squaredNorm(); });
  std::vector<Eigen::Vector3d> kept;
  // No ball holds the origin: no bound (outsideBallUnion's 0), and nothing to keep.
  if (centres.empty() || !(radius - centres.front().norm() > 0)) return kept;
  const double deepest = radius - centres.front().norm();
  std::vector<Eigen::Vector3d> candidates;
  for (const Eigen::Vector3d& c : centres) {
    const double depth = radius - c.norm();
    if (depth >= kShallowShare * deepest || (depth < 0 && -depth < reach)) candidates.push_back(c);
  }
  std::vector<double> gap(candidates.size(), std::numeric_limits<double>::infinity());
  std::size_t next = 0;
  while (kept.size() < static_cast<std::size_t>(kMaxBalls)) {
    kept.push_back(candidates[next]);
    double farthest = kDistinct * radius;
    bool any = false;
    for (std::size_t k = 0; k < candidates.size(); ++k) {
      gap[k] = std::min(gap[k], (candidates[k] - kept.back()).norm());
      if (gap[k] > farthest) {
        farthest = gap[k];
        next = k;
        any = true;
      }
    }
    if (!any) break;
  }
  return kept;
}

/// Surface points of `other` nearest the world point `towards`, within `radius` of c: NURBS patches' local minima
/// of the distance from a grid of starts each (a ring's hole seen from a ball's centre: points all round).
void addPointsNear(const PosedModel& other, const Eigen::Vector3d& towards, const Eigen::Vector3d& c, double radius,
                   std::vector<Eigen::Vector3d>& points) {
  if (other.model.type() != ModelType::Nurbs) return;
  const auto& m = static_cast<const NurbsModel&>(other.model);
  const nurbs::PointObjective distanceTo(other.toLocal(towards), m.localBoundingSphere().radius);
  for (std::size_t k = 0; k < m.patches().size(); ++k)
    for (int i = 0; i < kStartsPerSide; ++i)
      for (int j = 0; j < kStartsPerSide; ++j) {
        const double s = (i + 0.5) / kStartsPerSide, t = (j + 0.5) / kStartsPerSide;
        const nurbs::PatchHit h = nurbs::polish(m.patches()[k], static_cast<int>(k), distanceTo, s, t);
        const Eigen::Vector3d p = other.toWorld(h.point);
        if ((p - c).norm() < radius) points.push_back(p);
      }
}

}  // namespace

double outsideBallUnion(const std::vector<Eigen::Vector3d>& centres, double radius, Eigen::Vector3d* nearest,
                        Eigen::Vector3d* away) {
  if (nearest) nearest->setZero();
  if (away) away->setZero();
  const std::vector<Eigen::Vector3d>& v = centres;
  double reach = 0, deepest = 0;
  for (const Eigen::Vector3d& c : centres) {
    reach = std::max(reach, c.norm());
    deepest = std::max(deepest, radius - c.norm());
  }
  if (!(deepest > 0) || !(radius > 0)) return 0;  // the origin is outside every ball
  // Rounding: the candidates are found to ~ulps of the radius; one a few ulps inside a ball still counts as
  // outside (a lower least |t| is still a bound), and the result gives up as much.
  const double slack = 64 * kEps * (radius + reach);
  const auto outsideAll = [&](const Eigen::Vector3d& t) {
    return std::all_of(v.begin(), v.end(), [&](const Eigen::Vector3d& c) { return (t - c).norm() >= radius - slack; });
  };
  double least = std::numeric_limits<double>::infinity();
  const auto offer = [&](const Eigen::Vector3d& t) {
    if (t.norm() < least && outsideAll(t)) {
      least = t.norm();
      if (nearest) *nearest = t;
    }
  };
  const std::size_t n = v.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (v[i].norm() > 0) offer(v[i] * (1 - radius / v[i].norm()));  // the sphere's point nearest the origin
    for (std::size_t j = i + 1; j < n; ++j) {
      Eigen::Vector3d t;
      if (circleNearest(v[i], v[j], radius, t)) offer(t);
      for (std::size_t k = j + 1; k < n; ++k) {
        Eigen::Vector3d t0, t1;
        if (!triplePoints(v[i], v[j], v[k], radius, t0, t1)) continue;
        offer(t0);
        offer(t1);
      }
    }
  }
  // Every t outside the union is outside the deepest ball: at least radius − |v_i| from the origin.
  const double bound = std::isfinite(least) ? std::max(least, deepest) : deepest;
  if (away && nearest && std::isfinite(least)) {
    std::vector<Eigen::Vector3d> normals;
    for (const Eigen::Vector3d& c : v)
      if ((*nearest - c).norm() <= radius * (1 + kActive)) normals.push_back((*nearest - c).normalized());
    *away = offEvery(normals);
  }
  return std::max(0.0, bound - 2 * slack);
}

BallUnionBound ballUnionBound(const PosedModel& a, const PosedModel& b, const Eigen::Vector3d& escape) {
  BallUnionBound bound;
  for (const bool ballInB : {true, false}) {
    const PosedModel& container = ballInB ? b : a;
    const PosedModel& other = ballInB ? a : b;
    if (!container.model.isSolid() || other.model.type() != ModelType::Nurbs) continue;
    const Eigen::Vector3d c = container.toWorld(container.model.localBoundingSphere().center);
    const SurfacePoint s = container.closestWorld(c);
    const double radius = -s.signedDistance - s.error;  // proved inside the container
    if (!(s.signedDistance < 0) || !(radius > 0)) continue;
    // B moving by t keeps A's point p inside its ball while |t − (p − c)| < ρ; B's point q stays inside A's ball
    // while |t − (c − q)| < ρ.
    // The points nearest the ball where it starts, and where the escape leaves it (the last to let go: as B
    // moves, the nearest points slide; those at the escape bound it to its own length).
    // Points just outside the ball count too, where a way out shorter than the escape would meet them (a ball
    // off the ring's axis, moved away from the side it sinks into, meets the other side).
    const double reach = escape.allFinite() ? escape.norm() : 0;
    std::vector<Eigen::Vector3d> points, centres;
    addPointsNear(other, c, c, radius + reach, points);
    if (reach > 0)
      addPointsNear(other, ballInB ? Eigen::Vector3d(c + escape) : Eigen::Vector3d(c - escape), c, radius + reach,
                    points);
    for (const Eigen::Vector3d& p : points) centres.push_back(ballInB ? p - c : c - p);
    Eigen::Vector3d way, away;
    const double depth = outsideBallUnion(spreadDeepest(std::move(centres), radius, reach), radius, &way, &away);
    if (depth > bound.depth) bound = {depth, way, away};  // t is B's translation either way
  }
  return bound;
}

}  // namespace unidist::detail
