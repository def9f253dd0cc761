#include "generic/translation_depth.h"

#include "dispatch.h"
#include "generic/ball_union.h"
#include "generic/direction_cones.h"
#include "generic/surface_search.h"
#include "pairs/analytic.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <vector>

namespace unidist::detail {

namespace {

constexpr int kWitnessSteps = 4;   // balancing steps per witness (each: one point query per model)
constexpr int kMaxMarchSteps = 200;
constexpr int kPolishRounds = 8;
constexpr int kMaxConeLevel = 40;
constexpr int kTraceEvery = 4;  // after the first two levels, every this many cones popped try their axis
constexpr int kSeparationTestCost = 20;  // a pair separation test against a point query (measured: 10–50×)
// An exit farther than this fraction of its length beyond the proved overlap suggests sliding contact.
constexpr double kSlidingSuspicion = 0.05;
constexpr int kLiftedSearchSteps = 10;
constexpr int kSeedEvaluations = 4000;  // per surface, for seedOverlap
constexpr double kBallsReach = 1.1;     // inscribed balls' radii sum to this much of the escape they bound
constexpr int kBallUnionRounds = 3;  // ball-union bounds, each from the escape the last one's end led to

PosedModel movedBy(const PosedModel& b, const Eigen::Vector3d& t) {
  return {b.model, Eigen::Isometry3d(Eigen::Translation3d(t)) * b.X_WM};
}

/// A proved separating translation of B, with the contact it leaves.
struct Escape {
  double length = std::numeric_limits<double>::infinity();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d pointA = Eigen::Vector3d::Zero();  // on A, at the contact after the move
  Eigen::Vector3d contactNormal = Eigen::Vector3d::UnitZ();  // A toward the moved B there
  bool hasContact = false;
};

class DepthSearch {
 public:
  DepthSearch(const PosedModel& a, const PosedModel& b, const QueryContext& ctx) : a_(a), b_(b), ctx_(ctx) {
    verdict_ = ctx;
    verdict_.overlapVerdictOnly = true;
    verdict_.apartProofOnly = true;
    verdict_.tolerance = ctx.tolerance / 16;  // so a gap of a quarter tolerance can still be proved
  }

  int queries() const { return queries_; }
  /// Work done, in point queries; a separation test is counted as kSeparationTestCost of them.
  int cost() const { return queries_ + kSeparationTestCost * separationTests_; }

  /// The overlap witness at translation t: a point x (improved in place) that lies in A at depth dA and in
  /// B moved by t at depth dB. x in A with dB > 0 proves every translation within dB of t overlaps (x stays
  /// inside the moved B); x in the moved B with dA > 0 proves the same within dA (that point of B stays
  /// inside A). The value is the larger radius so proved; <= 0 proves nothing.
  double witness(const Eigen::Vector3d& t, Eigen::Vector3d& x) {
    double best = -std::numeric_limits<double>::infinity();
    Eigen::Vector3d bestX = x;
    for (int k = 0; k < kWitnessSteps; ++k) {
      const SurfacePoint pa = a_.closestWorld(x), pb = b_.closestWorld(x - t);
      queries_ += 2;
      const double dA = -pa.signedDistance, dB = -pb.signedDistance;
      const double none = -std::numeric_limits<double>::infinity();
      const double value = std::max(dA >= 0 ? dB : none, dB >= 0 ? dA : none);
      if (value > best) {
        best = value;
        bestX = x;
      }
      if (dA >= 0 && dB >= 0) {
        // In both: stay inside the deeper solid (a move no longer than its depth) and go deeper into the other.
        x -= dA >= dB ? Eigen::Vector3d(pb.normal * dA) : Eigen::Vector3d(pa.normal * dB);
        continue;
      }
      // Outside one of them: move along the inward normal of the shallower solid by half the difference (its
      // depth grows by about that, the other's shrinks by at most that: both are 1-Lipschitz).
      const double half = 0.5 * std::abs(dA - dB);
      if (!(half > 0.25 * ctx_.tolerance)) break;
      x -= (dA < dB ? pa.normal : pb.normal) * half;
    }
    x = bestX;
    return best;
  }

  /// Proves B moved by t interior-disjoint from A (true), with the separation answer in `out`.
  bool separatedAt(const Eigen::Vector3d& t, DistanceResult& out) {
    out = dispatchPair(a_, movedBy(b_, t), verdict_);
    ++separationTests_;
    return out.lowerBound >= 0;
  }

  /// B moved by t as an escape when it is proved apart there (no contact recorded), else none.
  Escape escapeAt(const Eigen::Vector3d& t) {
    Escape e;
    DistanceResult probe;
    if (!(t.norm() > 0) || !separatedAt(t, probe)) return e;
    e.length = t.norm();
    e.direction = t / e.length;
    return e;
  }

  /// A filter for escape tries along e: B moved along e just short of `length` must be proved apart. (A ray
  /// can leave the overlap set and re-enter it, so this can skip a shorter exit; escapes are only upper bounds,
  /// so a skip never makes the reported bounds wrong, and the depth's lower bound does not depend on it.)
  bool mayBeat(const Eigen::Vector3d& e, double length) {
    if (!std::isfinite(length)) return true;
    DistanceResult probe;
    return separatedAt((length - 0.25 * ctx_.tolerance) * e, probe);
  }

  /// March along `axis` from s0 (every ray of the cone of half-angle alpha is proved to overlap up to s0):
  /// returns the distance up to which every ray of the cone is proved to stay in the overlap set.
  double march(const Eigen::Vector3d& axis, double alpha, double s0, Eigen::Vector3d& x, double cap) {
    // A ray r·e of the cone at r in [s, s + ds] lies within 2 r sin(α/2) + ds of s·axis.
    const double spread = 2 * std::sin(0.5 * alpha);
    double s = s0;
    for (int step = 0; step < kMaxMarchSteps && s < cap; ++step) {
      const double w = witness(s * axis, x);
      const double ds = (w - spread * s) / (1 + spread);
      // A cone stops once its spread takes half of the witness (its quarters go on from there with half the
      // spread); a ray goes on to the tolerance.
      if (!(ds > 0.125 * ctx_.tolerance) || spread * s > 0.5 * w) break;
      // Shrink by a relative hair so the covered ball is strictly inside the witnessed one.
      s += ds * (1 - 1e-12);
    }
    return std::min(s, cap);
  }

  /// A proved escape t = s·e + push for the smallest s found, searching upward from `provedInside` (the ray
  /// overlaps up to there). `push` (tiny or zero) lifts B off a face it merely touches: the translated pair is
  /// then proved apart instead of touching, which a separation test cannot tell from crossing.
  Escape exitAlong(const Eigen::Vector3d& e, double provedInside, const Eigen::Vector3d& push, int maxSteps) {
    Escape esc;
    // A supporting-plane gap along e bounds the exit: B moved that far lies beyond A's support plane.
    const double beyond = std::max(0.0, -supportGapLowerBound(a_, b_, e));
    double lo = std::min(provedInside, beyond), hi = beyond * (1 + 1e-12) + ctx_.tolerance;
    DistanceResult atHi, probe;
    bool haveHi = false;
    // Exponential search above the proved part: the exit is usually within a few tolerances of it.
    int steps = 0;
    for (double step = 0.25 * ctx_.tolerance; lo + step < hi && steps < maxSteps; step *= 4, ++steps) {
      if (separatedAt((lo + step) * e + push, probe)) {
        hi = lo + step;
        atHi = probe;
        haveHi = true;
        break;
      }
      lo += step;
    }
    if (!haveHi && (steps >= maxSteps || !separatedAt(hi * e + push, atHi))) return esc;
    while (hi - lo > 0.25 * ctx_.tolerance) {
      const double mid = 0.5 * (lo + hi);
      if (separatedAt(mid * e + push, probe)) {
        hi = mid;
        atHi = probe;
      } else {
        lo = mid;
      }
    }
    const Eigen::Vector3d t = hi * e + push;
    esc.length = t.norm();
    esc.direction = t / esc.length;
    esc.pointA = atHi.pointA;
    esc.contactNormal = atHi.normal;
    esc.hasContact = true;
    return esc;
  }

  /// The exit along e; when it lies well beyond the part of the ray proved to overlap, B may be sliding along
  /// a face it touches, so the exit is tried again with B lifted a quarter tolerance off each candidate face
  /// (the contact normals seen so far, the axes of both models).
  Escape exitAlong(const Eigen::Vector3d& e, double provedInside) {
    Escape best = exitAlong(e, provedInside, Eigen::Vector3d::Zero(), std::numeric_limits<int>::max());
    if (!(best.length - provedInside > kSlidingSuspicion * best.length + ctx_.tolerance)) return best;
    std::vector<Eigen::Vector3d> lifts;
    for (const Escape& p : planes_) lifts.push_back(p.contactNormal);
    for (const Eigen::Vector3d& axis : axesOfBoth(a_, b_)) lifts.push_back(axis);
    for (const Eigen::Vector3d& u : lifts) {
      if (std::abs(u.dot(e)) > 0.99) continue;  // along the ray: no lift off a face the ray slides on
      const Escape lifted = exitAlong(e, provedInside, 0.25 * ctx_.tolerance * u, kLiftedSearchSteps);
      if (lifted.length < best.length) best = lifted;
    }
    return best;
  }

  /// Exit along e, then re-aim along the contact normal found there while that shortens the escape.
  Escape polishedExit(const Eigen::Vector3d& e0, Eigen::Vector3d x) {
    Escape best;
    Eigen::Vector3d e = e0;
    for (int round = 0; round < kPolishRounds; ++round) {
      const double inside = march(e, 0, 0, x, best.length);
      const Escape esc = exitAlong(e, inside);
      if (!(esc.length < best.length - 0.25 * ctx_.tolerance)) {
        if (esc.length < best.length) best = esc;
        break;
      }
      best = esc;
      const Escape crease = creaseExit(esc);
      if (crease.length < best.length) best = crease;
      // The boundary of the overlap set at the escape has the contact normal as its normal: its tangent plane's
      // closest point to the origin lies along that normal.
      const Eigen::Vector3d n = esc.contactNormal;
      if (!(n.dot(esc.direction) > 0) || !n.allFinite() || (n - e).norm() < 1e-15) break;
      e = n.normalized();
    }
    return best;
  }

  int separationTests() const { return separationTests_; }

  /// Where two of the escapes' contact planes meet, the overlap set has a crease (a concave corner of its
  /// boundary, e.g. a cube in a notch that must clear two walls): the closest point of the crease line to the
  /// origin is a direction no polish along single normals reaches. Tries the newest plane with each earlier one.
  Escape creaseExit(const Escape& newest) {
    Escape best;
    if (!newest.hasContact) return best;
    const Eigen::Vector3d n1 = newest.contactNormal;
    const double c1 = newest.length * newest.direction.dot(n1);
    for (const Escape& other : planes_) {
      const Eigen::Vector3d n2 = other.contactNormal;
      const double c2 = other.length * other.direction.dot(n2);
      const double g = n1.dot(n2), det = 1 - g * g;
      if (!(det > 1e-12)) continue;
      const Eigen::Vector3d t = ((c1 - g * c2) * n1 + (c2 - g * c1) * n2) / det;
      const double len = t.norm();
      if (!(len > 0) || len >= best.length || len >= newest.length) continue;
      Eigen::Vector3d x = newest.pointA;
      const Escape esc = exitAlong(t / len, march(t / len, 0, 0, x, newest.length));
      if (esc.length < best.length) best = esc;
    }
    if (planes_.size() < kMaxPlanes) planes_.push_back(newest);
    return best;
  }

 private:
  const PosedModel& a_;
  const PosedModel& b_;
  const QueryContext& ctx_;
  QueryContext verdict_;
  int queries_ = 0;
  int separationTests_ = 0;
  static constexpr std::size_t kMaxPlanes = 16;
  std::vector<Escape> planes_;  // escapes whose contact planes the crease candidates combine
};

/// A ball inside the solid tangent at `point` (on its surface; `inward` its inward unit normal there): the proved
/// radius of the ball about point + radius·inward that lies inside (its centre inside, its distance to the
/// surface less the point query's error), or 0 where the centre is not inside.
double inscribedRadius(const PosedModel& solid, const Eigen::Vector3d& point, const Eigen::Vector3d& inward,
                       double radius) {
  const SurfacePoint s = solid.closestWorld(point + radius * inward);
  return s.signedDistance < 0 ? std::max(0.0, -s.signedDistance - s.error) : 0.0;
}

/// A lower bound on the depth from two balls, one inside each solid, tangent to the surfaces at the escape's
/// contact pair and centred on its normal: every translation separating the solids separates the balls, whose
/// depth is r_A + r_B − |c_A − c_B| (exactly the escape's length when both fit: the collinear-normal pair's
/// penetration, as deep as a ball sunk in a ring's tube, where no surface point is that deep). Radii: shares of
/// the escape's length (their sum must reach it), each tried until a ball fits; 0 when none does.
double inscribedBallsBound(const PosedModel& a, const PosedModel& b, const Escape& escape, double tolerance) {
  if (!escape.hasContact || !std::isfinite(escape.length) || !(escape.length > 0)) return 0;
  const Eigen::Vector3d n = escape.contactNormal;  // A's outward normal at the contact = B's inward one there
  if (!(std::abs(n.norm() - 1) < 1e-9)) return 0;
  const Eigen::Vector3d pA = escape.pointA, pB = escape.pointA - escape.length * escape.direction;
  // Balls that do not quite fit (a radius past the surface's curvature, or a contact pair not yet collinear)
  // still bound the depth with the radii they get: the best of the shares is kept, and the first whose balls
  // both fit ends the tries.
  double bound = 0;
  for (const double shareA : {0.55, 0.25, 0.85, 0.1, 0.97}) {
    const double radiusA = shareA * kBallsReach * escape.length, radiusB = (1 - shareA) * kBallsReach * escape.length;
    // A centre outside its solid (radius 0) holds no ball: there is no bound then.
    const double rA = inscribedRadius(a, pA, -n, radiusA);
    if (!(rA > 0)) continue;
    const double rB = inscribedRadius(b, pB, n, radiusB);
    if (!(rB > 0)) continue;
    const Eigen::Vector3d cA = pA - radiusA * n, cB = pB + radiusB * n;
    bound = std::max(bound, rA + rB - (cA - cB).norm());
    if (rA >= radiusA - 0.125 * tolerance && rB >= radiusB - 0.125 * tolerance) break;
  }
  return bound;
}

struct OpenCone {
  DirectionCone cone;
  double provedExit;  // every ray of the cone overlaps up to here
  Eigen::Vector3d witness;
  bool operator>(const OpenCone& o) const { return provedExit > o.provedExit; }
};

}  // namespace

DistanceResult translationalDepth(const PosedModel& a, const PosedModel& b, const QueryContext& ctx,
                                  const OverlapSeed& seed, DepthScope scope) {
  const double tol = ctx.tolerance;
  DepthSearch search(a, b, ctx);
  const long budget = 3L * std::max(1000, ctx.maxIterations);  // in point queries (cost())

  Escape best;
  best.length = seed.knownEscape;
  best.direction = seed.knownEscapeDirection;
  double provedDepth = std::max(0.0, seed.provedDepth);
  // A supporting plane's escape has a contact too, for the balls: A's support point along it, and the point of B
  // that the escape brings onto it (two tori stacked by the escape touch along a circle in that plane).
  if (std::isfinite(best.length) && best.length - provedDepth > tol) {
    Escape plane = best;
    plane.pointA = a.supportWorld(plane.direction);
    plane.contactNormal = plane.direction;
    plane.hasContact = true;
    provedDepth = std::max(provedDepth, inscribedBallsBound(a, b, plane, tol));
  }
  auto consider = [&](const Escape& e) {
    // Any escape's contact bounds the depth from below (the balls need not be at the shortest escape's).
    if (e.hasContact && best.length - provedDepth > tol)
      provedDepth = std::max(provedDepth, inscribedBallsBound(a, b, e, tol));
    // An escape with its contact points beats a supporting-plane escape (no points) within a quarter tolerance.
    if (e.length < best.length || (!best.hasContact && e.hasContact && e.length <= best.length + 0.25 * tol)) best = e;
  };
  // A supporting plane's escape that already meets the proved depth needs no search for contact points (a shallow
  // overlap's bisection along a face B slides on, lifted off it in every direction: a third of a second).
  if (best.length - provedDepth > tol) consider(search.polishedExit(seed.direction, seed.deepPoint));
  // Both models' axes leaning the seed's way: a ball sunk in a ring's hole leaves up the ring's axis, the one way
  // out that no single contact's normal shows.
  for (const Eigen::Vector3d& axis : axesOfBoth(a, b))
    if (best.length - provedDepth > tol && axis.dot(seed.direction) > 0 && search.mayBeat(axis, best.length))
      consider(search.polishedExit(axis, seed.deepPoint));
  // All the contacts of a round solid at once, where it starts and where the best escape leaves it (a ball sunk
  // in a ring's hole leaves only up the axis, deeper than any point is in).
  // Its end, where the contacts let go, is the next way out tried: there the moved solid touches them all, so
  // it is lifted off them by a little more each time until it is proved apart (off the ring's axis the
  // shortest escape leans, and past that point the ray re-enters the overlap, so no exit along it is found).
  // The next bound takes its points where that escape leaves.
  Eigen::Vector3d target = best.length * best.direction;
  for (int round = 0; round < kBallUnionRounds && std::isfinite(best.length) && best.length - provedDepth > tol;
       ++round) {
    const BallUnionBound u = ballUnionBound(a, b, target);
    provedDepth = std::max(provedDepth, u.depth);
    if (!(best.length - provedDepth > tol) || !(u.away.norm() > 0)) break;
    const double before = best.length;
    for (double lift = 0.25 * tol; lift < best.length - u.way.norm(); lift *= 4) {
      const Escape e = search.escapeAt(u.way + lift * u.away);
      if (!std::isfinite(e.length)) continue;
      consider(e);
      break;
    }
    if (!(best.length < before)) break;
    target = u.way;
  }
  // In a deep overlap the deepest point's normal can point the long way out (B's point nearest A's middle
  // leaves through A's far side); the line between the models' centres is the other natural first guess.
  const Eigen::Vector3d centres = b.toWorld(b.model.localBoundingSphere().center) -
                                  a.toWorld(a.model.localBoundingSphere().center);
  if (scope == DepthScope::Full && centres.norm() > 0 && search.mayBeat(centres.normalized(), best.length))
    consider(search.polishedExit(centres.normalized(), seed.deepPoint));

  std::priority_queue<OpenCone, std::vector<OpenCone>, std::greater<OpenCone>> open;
  bool searched = false;  // whether the cones cover every direction (else only provedDepth is known)
  auto lowerBound = [&] {
    if (!searched) return provedDepth;
    return std::max(provedDepth, open.empty() ? best.length : open.top().provedExit);
  };
  auto push = [&](const DirectionCone& c, double from, Eigen::Vector3d x) {
    const double reached = search.march(c.axis, c.halfAngle, from, x, best.length);
    open.push({c, reached, x});
  };
  if (scope == DepthScope::Full && best.length - provedDepth > tol) {
    for (const DirectionCone& c : cubeMapCones(2)) push(c, 0, seed.deepPoint);
    searched = true;
  }
  int popped = 0;
  while (!open.empty() && best.length - lowerBound() > tol && search.cost() < budget) {
    const OpenCone top = open.top();
    open.pop();
    ++popped;
    // Try the cone's axis for a better escape now and then (each try costs tens of separation tests), unless
    // one test finds B not apart just short of the best escape along it: the axis then most likely exits
    // later, while the cones around a shorter escape have axes that pass as they shrink.
    if ((top.cone.level <= 1 || popped % kTraceEvery == 0) && search.mayBeat(top.cone.axis, best.length))
      consider(search.polishedExit(top.cone.axis, top.witness));
    if (top.cone.level >= kMaxConeLevel) {
      open.push(top);  // as fine as directions go; keep its bound
      break;
    }
    for (const DirectionCone& child : splitCone(top.cone)) push(child, top.provedExit, top.witness);
  }
  // Cones proved beyond the best escape never matter; everything left bounds the depth from below.
  const double lower = std::min(lowerBound(), best.length);

  DistanceResult r;
  r.method = "translation-depth-bnb";
  r.iterations = search.queries() + search.separationTests();
  r.distance = -best.length;
  r.normal = best.direction;
  if (best.hasContact) {
    r.pointA = best.pointA;
    r.pointB = best.pointA - best.length * best.direction;
  } else {
    // Only a supporting-plane escape is known: the two support points touch the planes, but only one of them is
    // the contact: of B's support point and where it lands on A's support plane, or of A's and where it lands on
    // B's, the pair whose landing point lies on the other surface (a ball on a table: the ball's bottom).
    const Eigen::Vector3d move = best.length * best.direction;
    const Eigen::Vector3d onB = b.supportWorld(-best.direction), onA = a.supportWorld(best.direction);
    const bool fromA = std::abs(b.closestWorld(onA - move).signedDistance) <
                       std::abs(a.closestWorld(onB + move).signedDistance);
    r.pointA = fromA ? onA : Eigen::Vector3d(onB + move);
    r.pointB = fromA ? Eigen::Vector3d(onA - move) : onB;
  }
  r.lowerBound = -best.length;
  r.upperBound = -lower;
  settleStatus(r, tol);
  return r;
}

namespace {

constexpr int kDeepenSteps = 200;
constexpr double kCoarseDeepening = 1e-5;  // seedFromContact's first descents stop at this fraction of the size
constexpr double kContactNudgeReach = 1.0;  // seedFromContact's starts reach as far in as the larger model's radius

/// One surface's deepest point inside the other solid, from the surface point nearest `start`.
/// Returns the depth reached, proved (0 when `start` is not near a point of `surface` inside `solid`); `realised`
/// receives it as the point query realised it, before its error bound.
/// `stop`: the step at which the descent ends (default 1e-3 × tolerance); `firstStep`: its first step (default the
/// start's depth, at least the tolerance).
double deepenOn(const PosedModel& surface, const PosedModel& solid, const Eigen::Vector3d& start, double tolerance,
                Eigen::Vector3d& deepest, Eigen::Vector3d& outward, double& realised, double stop = -1,
                double firstStep = -1) {
  Eigen::Vector3d p = surface.closestWorld(start).point;
  SurfacePoint in = solid.closestWorld(p);
  realised = 0;
  if (!(in.signedDistance < 0)) return 0;
  if (!(stop > 0)) stop = 1e-3 * tolerance;
  double step = firstStep > 0 ? firstStep : std::max({-in.signedDistance, tolerance, 2 * stop});
  for (int k = 0; k < kDeepenSteps && step > stop; ++k) {
    const Eigen::Vector3d q = surface.closestWorld(p - step * in.normal).point;
    const SurfacePoint atQ = solid.closestWorld(q);
    if (atQ.signedDistance < in.signedDistance) {
      p = q;
      in = atQ;
      step *= 1.5;
    } else {
      step *= 0.5;
    }
  }
  deepest = p;
  outward = in.normal;
  realised = -in.signedDistance;
  // Proved: the point query's distance is realised, the true one at most its error less.
  return std::max(0.0, -in.signedDistance - in.error);
}

/// deepenOn for `surface` (B's when bInA, else A's) in the other solid, its point kept in the seed when deeper:
/// B's surface inside A leaves along A's outward normal; A's surface inside B makes B leave against B's.
double deepenInto(const PosedModel& a, const PosedModel& b, bool bInA, const Eigen::Vector3d& start, double tolerance,
                  OverlapSeed& seed, double stop = -1, double firstStep = -1) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero(), n = Eigen::Vector3d::Zero();
  double realised = 0;
  const double d = deepenOn(bInA ? b : a, bInA ? a : b, start, tolerance, p, n, realised, stop, firstStep);
  if (d > seed.provedDepth) {
    seed.provedDepth = d;
    seed.realisedDepth = realised;
    seed.deepPoint = p;
    seed.direction = bInA ? n : Eigen::Vector3d(-n);
  }
  return d;
}

/// Lowers seed.knownEscape by the supporting-plane escape along unit u: B moved this far along u is beyond A.
void addPlaneEscape(const PosedModel& a, const PosedModel& b, const Eigen::Vector3d& u, OverlapSeed& seed) {
  const double escape = std::max(0.0, -supportGapLowerBound(a, b, u));
  if (escape < seed.knownEscape) {
    seed.knownEscape = escape;
    seed.knownEscapeDirection = u;
  }
}

}  // namespace

void deepenSeed(const PosedModel& a, const PosedModel& b, double tolerance, OverlapSeed& seed) {
  const Eigen::Vector3d start = seed.deepPoint;
  deepenInto(a, b, true, start, tolerance, seed);
  deepenInto(a, b, false, start, tolerance, seed);
}

OverlapSeed seedFromContact(const PosedModel& a, const PosedModel& b, const Eigen::Vector3d& contact_W,
                            double tolerance) {
  OverlapSeed seed;
  seed.deepPoint = contact_W;
  const double size = std::max(a.model.localBoundingSphere().radius, b.model.localBoundingSphere().radius);
  // Both descents stop coarse; only the deeper one is refined to the tolerance (the other may be converging on
  // a solid's medial axis, a torus's core circle, where every point query meets a circle of equal distances).
  const double coarse = std::max(1e-3 * tolerance, kCoarseDeepening * size);
  bool deeperIsBInA = true;
  addPlaneEscapes(a, b, seed);
  // A side as deep as a supporting plane's escape already meets the upper bound: the other is not tried.
  for (const bool bInA : {true, false}) {
    if (seed.provedDepth >= seed.knownEscape - 0.25 * tolerance) break;
    const PosedModel& solid = bInA ? a : b;
    const Eigen::Vector3d inward = -solid.closestWorld(contact_W).normal;
    const auto deepenFrom = [&](const Eigen::Vector3d& start) {
      const double before = seed.provedDepth;
      const double d = deepenInto(a, b, bInA, start, tolerance, seed, coarse);
      if (seed.provedDepth > before) deeperIsBInA = bInA;
      return d > 0;
    };
    // Where the surfaces cross at a small angle the surface point nearest a start just inside the solid can lie
    // outside it: the start moves further in until one does. Where none does (the contact's normal is not the way
    // in: a contact off the solid's surface, a point deep inside it), the surface point nearest the solid's centre
    // is the start (for a ball, exactly the deepest).
    bool found = false;
    for (double nudge = tolerance; nudge < kContactNudgeReach * size && !found; nudge *= 8)
      found = deepenFrom(contact_W + nudge * inward);
    if (!found) deepenFrom(solid.toWorld(solid.model.localBoundingSphere().center));
  }
  if (seed.provedDepth > 0) deepenInto(a, b, deeperIsBInA, seed.deepPoint, tolerance, seed, -1, 2 * coarse);
  addPlaneEscape(a, b, seed.direction, seed);  // the deepest point's normal: the axes were tried above
  return seed;
}

std::optional<DistanceResult> shallowDepth(const PosedModel& a, const PosedModel& b, const QueryContext& ctx,
                                           const Eigen::Vector3d& contact_W) {
  const OverlapSeed seed = seedFromContact(a, b, contact_W, ctx.tolerance);
  if (!(seed.provedDepth > 0)) return std::nullopt;
  DistanceResult r = translationalDepth(a, b, ctx, seed, DepthScope::SeedEscape);
  // Not certified, but the deepest point's realised depth meets the proved escape: the bracket is as narrow as
  // the point queries can prove (a sliver 1e-8 deep along a circle, stacked rings), and the full search, made of
  // the same queries, would spend its budget for a wider one. The answer goes out bounded.
  const bool realisedMeetsEscape = r.upperBound < 0 && -r.lowerBound - seed.realisedDepth <= ctx.tolerance;
  if (r.status != Status::Certified && !realisedMeetsEscape) return std::nullopt;
  return r;
}

void addPlaneEscapes(const PosedModel& a, const PosedModel& b, OverlapSeed& seed) {
  // The world's axes and both models' own (a ring's axis is the way a ring stacked on another leaves).
  addPlaneEscape(a, b, seed.direction, seed);
  for (int i = 0; i < 3; ++i)
    for (double sign : {1.0, -1.0}) addPlaneEscape(a, b, sign * Eigen::Vector3d::Unit(i), seed);
  for (const Eigen::Vector3d& axis : axesOfBoth(a, b)) addPlaneEscape(a, b, axis, seed);
}

OverlapSeed seedOverlap(const PosedModel& a, const PosedModel& b, const QueryContext& ctx) {
  OverlapSeed seed;
  double deepest = std::numeric_limits<double>::infinity(), proved = 0;
  for (bool ofA : {true, false}) {
    const PosedModel& surface = ofA ? a : b;
    const PosedModel& field = ofA ? b : a;
    const Eigen::Vector3d start = surface.supportWorld(field.toWorld(field.model.localBounds().center()) -
                                                       surface.toWorld(surface.model.localBounds().center()));
    const SurfaceMinimum m = minimizeFieldOverSurface(surface, field, fieldValue(field, start), start,
                                                      0.5 * ctx.tolerance, kSeedEvaluations, kSeedEvaluations);
    if (m.value < deepest) {
      deepest = m.value;
      const SurfacePoint onField = field.closestWorld(m.point);
      proved = std::max(0.0, -onField.signedDistance - onField.error);  // realised, less the query's error
      seed.deepPoint = m.point;
      seed.direction = ofA ? Eigen::Vector3d(-onField.normal) : onField.normal;  // the way B leaves
    }
  }
  seed.provedDepth = proved;
  addPlaneEscapes(a, b, seed);
  return seed;
}

}  // namespace unidist::detail
