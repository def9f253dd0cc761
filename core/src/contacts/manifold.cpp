// Simulation contacts (unidist/contact_manifold.h): the local minima of unidist::contacts(), a resting patch
// filled in by tilting A, every point moved onto its local support point, a warm start that re-measures cached
// witness points while the pair moves less than a guard distance, and the reduction to the engine's count.
#include "unidist/contact_manifold.h"

#include "contacts/box_box_contacts.h"
#include "contacts/pair_motion.h"
#include "contacts/reduce.h"
#include "contacts/rounding.h"
#include "contacts/warm_projections.h"
#include "unidist/distance.h"
#include "unidist/primitives.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

namespace unidist {
namespace {

using contact::boundedDiagonal;
using contact::relativeMotion;

/// Tilt used to find the rest of a resting patch: large enough that the far side of a flat or circular patch
/// is clearly the deepest point of the tilted pose, small enough that the tilted pose is still "this contact".
constexpr double kPatchTilt = 0.05;
/// Warm-start guard in units of the query tolerance: motion below it changes a re-measured witness pair's
/// distance by second-order amounts only (curvature × guard²), far below the tolerance.
constexpr double kGuardInTolerances = 10;
/// Lift of A off B before measuring (at least the margin): resting overlaps are a few tolerances deep.
constexpr double kSkinInTolerances = 50;
/// deepen(): how far the support probe goes, in units of the model's bounding radius (each step shrinks a
/// point's offset from its support point by about that over the curvature radius), and how many steps a global
/// search's contacts and a warm-started contact get.
constexpr double kDeepenReach = 100;
constexpr int kDeepenRounds = 5;
constexpr int kDeepenRoundsPerUpdate = 3;
/// deepen() stops once a step moves the point less than this many bounding radii (converged: a closest point
/// to a far probe is itself only that sharp along a curved surface, the distance to the probe being flat there),
/// and accepts a step that makes the contact shallower by at most this many tolerances (rounding, see deepen()).
constexpr double kDeepenConverged = 1e-6;
constexpr double kDeepenSlackInTolerances = 1e-3;
/// Inside B, deepen() keeps a step only if B's normal there is within ~1.4° of the contact normal (cosine).
constexpr double kDeepenInsideAgreement = 0.9997;

/// How deepen() runs: at most `rounds` support steps, each kept unless shallower by more than `slack`; its
/// projections local from the contact's own places when `local` is set (the warm start), exact otherwise.
struct DeepenSteps {
  int rounds;
  double slack;
  contact::WarmProjections* local = nullptr;
};

/// Where a point sits on its model: its feature and surface parameters (the hint of a local projection).
struct Place {
  int feature = 0;
  Eigen::Vector2d param = Eigen::Vector2d::Zero();
};
Place placeA(const Contact& c) { return {c.featureA, c.paramA}; }
Place placeB(const Contact& c) { return {c.featureB, c.paramB}; }

double defaultSimulationTolerance(const Model& a, const Model& b) {
  const double d = std::min(boundedDiagonal(a), boundedDiagonal(b));
  return std::isfinite(d) && d > 0 ? 1e-4 * d : 1e-9;
}

/// Where the two points are apart, the normal is their direction (exactly the contract's pointB − pointA =
/// distance · normal); the surface normal is kept only where they coincide.
void normalFromPoints(Contact& c) {
  const Eigen::Vector3d gap = c.pointB - c.pointA;
  const double scale = 1 + c.pointA.cwiseAbs().maxCoeff();
  const double length = gap.norm();
  if (length > 1e-12 * scale && c.distance != 0) c.normal = gap / std::copysign(length, c.distance);
}

/// The contact of the untilted pair at a point of A's surface (at place onA): B's closest point to it, found
/// near nearB when `local` is set (world frame; X_BW is X_WB's inverse, computed once by the caller: this runs
/// for every cached contact every step).
Contact remeasureFromA(const Eigen::Vector3d& pA_W, const Place& onA, const Model& b, const Place& nearB,
                       const Eigen::Isometry3d& X_WB, const Eigen::Isometry3d& X_BW, contact::WarmProjections* local) {
  const SurfacePoint s = contact::projectOnto(local, b, X_BW * pA_W, nearB.feature, nearB.param);
  Contact c;
  c.pointA = pA_W;
  c.pointB = X_WB * s.point;
  c.distance = s.signedDistance;
  c.errorBound = s.error;
  c.normal = -(X_WB.linear() * s.normal);  // B's outward normal points at A: the contact normal is its opposite
  c.featureA = onA.feature, c.paramA = onA.param;
  c.featureB = s.feature, c.paramB = s.param;
  normalFromPoints(c);
  return c;
}

/// The same from a point of B's surface (A's closest point to it).
Contact remeasureFromB(const Eigen::Vector3d& pB_W, const Place& onB, const Model& a, const Place& nearA,
                       const Eigen::Isometry3d& X_WA, const Eigen::Isometry3d& X_AW, contact::WarmProjections* local) {
  const SurfacePoint s = contact::projectOnto(local, a, X_AW * pB_W, nearA.feature, nearA.param);
  Contact c;
  c.pointA = X_WA * s.point;
  c.pointB = pB_W;
  c.distance = s.signedDistance;
  c.errorBound = s.error;
  c.normal = X_WA.linear() * s.normal;
  c.featureA = s.feature, c.paramA = s.param;
  c.featureB = onB.feature, c.paramB = onB.param;
  normalFromPoints(c);
  return c;
}

/// The poses a local update needs, inverted and composed once per call rather than once per cached contact.
struct UpdateFrames {
  UpdateFrames(const Eigen::Isometry3d& X_WA, const Eigen::Isometry3d& X_WB, const Eigen::Isometry3d& X_AB0, double slack,
               contact::WarmProjections* local)
      : X_WA(X_WA), X_WB(X_WB), X_AW(X_WA.inverse()), X_BW(X_WB.inverse()), X_WB_fromCachedA(X_WB * X_AB0.inverse()),
        slack(slack), local(local) {}
  const Eigen::Isometry3d& X_WA;
  const Eigen::Isometry3d& X_WB;
  const Eigen::Isometry3d X_AW, X_BW;
  const Eigen::Isometry3d X_WB_fromCachedA;  ///< a point of B cached in A's frame at the search → world now
  const double slack;                        ///< deepen()'s
  contact::WarmProjections* const local;     ///< the cache's local projections
};

/// The same contact with the roles of A and B exchanged.
Contact swapped(const Contact& c) {
  Contact s = c;
  std::swap(s.pointA, s.pointB);
  std::swap(s.featureA, s.featureB);
  std::swap(s.paramA, s.paramB);
  s.normal = -c.normal;
  return s;
}

/// Moves A's point of a contact toward A's locally deepest point along `n` (the contact normal, A → B) and
/// re-measures B's point from it: A's point of a local minimum is A's local support point in the normal
/// direction. The support step is A's closest point to a probe pushed far along n (reach ≫ A's size: on a
/// curved surface each step shrinks the point's offset from the support point by reach / A's radius), so a
/// point on a ball reaches the true bottom in two steps instead of sitting where a coarse tolerance or the
/// last step's rolling left it — an offset a solver turns into a torque, and a resting ball into a rolling one.
///  * n stays fixed: a re-measured normal is tilted wherever B's point sits on an edge.
///  * A walk that does not converge (each step at least half the last) is a flat face slightly tilted against
///    n, where every step slides the point reach × tilt further: the point was as good a contact as any (a
///    corner of the face, which keeps the patch spread), and it is kept.
///  * A step is kept unless it makes the contact shallower by more than `slack`: near the bottom of a ball the
///    depth changes by offset²/(2r), below the rounding of single-precision engine poses, so "strictly deeper"
///    would stop anywhere within ~0.1 mm of it.
///  * Inside B, a step is kept only while B's nearest face still faces along n: deeper in, B's closest point
///    belongs to whichever face is nearest (a box's side), not to this contact.
/// Point clouds are left alone (their points are the features), and half-spaces (flat everywhere).
Contact deepen(const Contact& c, const Eigen::Vector3d& n, const Model& a, const Eigen::Isometry3d& X_WA,
               const Eigen::Isometry3d& X_AW, const Model& b, const Eigen::Isometry3d& X_WB,
               const Eigen::Isometry3d& X_BW, const DeepenSteps& steps) {
  const double radius = a.localBoundingSphere().radius;
  if (a.type() == ModelType::PointCloud || !std::isfinite(radius)) return c;  // a half-space is flat everywhere
  const Eigen::Vector3d along = kDeepenReach * radius * n;
  Contact best = c;
  double lastMove = std::numeric_limits<double>::infinity();
  for (int round = 0; round < steps.rounds; ++round) {
    const SurfacePoint s = contact::projectOnto(steps.local, a, X_AW * (best.pointA + along), best.featureA, best.paramA);
    const Contact next = remeasureFromA(X_WA * s.point, {s.feature, s.param}, b, placeB(best), X_WB, X_BW, steps.local);
    if (!(next.distance <= best.distance + steps.slack)) break;
    if (next.distance < 0 && next.normal.dot(n) < kDeepenInsideAgreement) break;  // another face's depth
    const double move = (next.pointA - best.pointA).norm();
    if (move <= kDeepenConverged * radius) return next;
    if (move > 0.5 * lastMove) return c;  // sliding over a flat face
    best = next;
    lastMove = move;
  }
  return best;
}

/// deepen() on both sides along the contact's normal: B's point toward B's locally deepest point against A,
/// then A's.
Contact deepenBoth(const Contact& c, const Model& a, const Eigen::Isometry3d& X_WA, const Eigen::Isometry3d& X_AW,
                   const Model& b, const Eigen::Isometry3d& X_WB, const Eigen::Isometry3d& X_BW, const DeepenSteps& steps) {
  const Eigen::Vector3d n = c.normal;
  const Contact fromB = swapped(deepen(swapped(c), -n, b, X_WB, X_BW, a, X_WA, X_AW, steps));
  return deepen(fromB, n, a, X_WA, X_AW, b, X_WB, X_BW, steps);
}

/// A cached witness pair re-measured at the current poses: each point rides with its model and is re-projected
/// onto the other; the deeper of the two readings wins (it is the one anchored at the sharper feature — a box
/// corner's depth, not the zero a face point reads against that corner), and one deepening round lets a point
/// on a rolling curved surface follow its support point. The normal is the global search's, riding with B, and
/// the distance is measured along it (B's point is kept on B's tangent plane there): re-deriving it from the
/// two points would tilt it wherever a point re-projects onto an edge — a flush corner a few hundredths of a
/// millimetre past the face below it reads a normal tilted by gap/offset, up to 1e-2 rad, and Bullet's
/// friction walks a resting stack on such tilts. Within the guard the true normal turns by at most the guard
/// over the radius of curvature.
Contact remeasure(const Contact& cached_A, const Model& a, const Model& b, const UpdateFrames& f) {
  const Eigen::Vector3d pB_W = f.X_WB_fromCachedA * cached_A.pointB;  // B's point rides with B
  Contact c = remeasureFromA(f.X_WA * cached_A.pointA, placeA(cached_A), b, placeB(cached_A), f.X_WB, f.X_BW, f.local);
  if (a.isSolid()) {  // without an inside, B's point would read an unsigned distance
    const Contact fromB = remeasureFromB(pB_W, placeB(cached_A), a, placeA(cached_A), f.X_WA, f.X_AW, f.local);
    if (fromB.distance < c.distance) c = fromB;
  }
  const Eigen::Vector3d n = f.X_WB_fromCachedA.linear() * cached_A.normal;
  c.normal = n;
  c = deepenBoth(c, a, f.X_WA, f.X_AW, b, f.X_WB, f.X_BW, {kDeepenRoundsPerUpdate, f.slack, f.local});
  c.normal = n;
  const double measured = c.distance;
  c.distance = (c.pointB - c.pointA).dot(n);
  c.pointB = c.pointA + c.distance * n;
  c.errorBound += std::abs(c.distance - measured);  // the reading along n is not the measured one
  return c;
}

/// Tilts A about two axes perpendicular to the deepest contact's normal and keeps each tilted pose's deepest
/// point of A toward B when it is a contact of the untilted pair within the margin (re-measured at the true
/// poses, then refined to the local minimum of its region). The tilted deepest point is A's support point in
/// the tilted normal direction: no pair query, and exact against a flat B (against a curved one the
/// re-measurement decides).
void fillPatch(const Model& a, const Eigen::Isometry3d& X_WA, const Model& b, const Eigen::Isometry3d& X_WB,
               double margin, double slack, std::vector<Contact>& cs) {
  const Eigen::Vector3d n = cs.front().normal;
  const Eigen::Vector3d u = n.unitOrthogonal(), v = n.cross(u);
  const Eigen::Isometry3d X_AW = X_WA.inverse(), X_BW = X_WB.inverse();
  std::vector<Contact> found;
  for (const Eigen::Vector3d& axis : {u, v}) {
    for (double sign : {1.0, -1.0}) {
      const Eigen::Matrix3d tilt = Eigen::AngleAxisd(sign * kPatchTilt, axis).toRotationMatrix();
      const Eigen::Vector3d dir_A = X_WA.linear().transpose() * (tilt.transpose() * n);
      const Eigen::Vector3d pA = a.support(dir_A);
      const SurfacePoint onA = a.closestPoint(pA);
      Contact c = remeasureFromA(X_WA * pA, {onA.feature, onA.param}, b, {}, X_WB, X_BW, nullptr);
      if (c.distance > margin) continue;
      found.push_back(deepen(c, c.normal, a, X_WA, X_AW, b, X_WB, X_BW, {kDeepenRounds, slack}));
    }
  }
  cs.insert(cs.end(), found.begin(), found.end());
}

/// Whether every point of A is farther than `margin` from every point of B, proved from the models' surface
/// cells (best-first, splitting the larger cell of the closest pair) within a small budget; false when
/// unproved. Most pairs a broadphase hands over are apart: this spares them the global query (seconds for two
/// curved models whose minimum is a circle, like a ball in a ring).
bool provablyApart(const Model& a, const Eigen::Isometry3d& X_WA, const Model& b, const Eigen::Isometry3d& X_WB,
                   double margin) {
  constexpr int kBudget = 400;
  struct Pair {
    double bound;
    SurfaceCell ca, cb;
    bool operator>(const Pair& o) const { return bound > o.bound; }
  };
  const std::vector<SurfaceCell> rootsA = a.surfaceCells(), rootsB = b.surfaceCells();
  if (rootsA.empty() || rootsB.empty()) return false;  // unbounded (a half-space): nothing to prove with
  auto bound = [&](const SurfaceCell& x, const SurfaceCell& y) {
    return (X_WA * x.center - X_WB * y.center).norm() - x.radius - y.radius;
  };
  std::priority_queue<Pair, std::vector<Pair>, std::greater<Pair>> open;
  for (const SurfaceCell& x : rootsA)
    for (const SurfaceCell& y : rootsB) open.push({bound(x, y), x, y});
  std::vector<SurfaceCell> parts;
  for (int step = 0; step < kBudget && !open.empty(); ++step) {
    const Pair p = open.top();
    if (p.bound > margin) return true;  // the closest remaining pair is apart: so is every other
    open.pop();
    parts.clear();
    const bool splitA = p.ca.radius >= p.cb.radius;
    (splitA ? a : b).splitCell(splitA ? p.ca : p.cb, parts);
    if (parts.empty()) return false;  // cannot refine further
    for (const SurfaceCell& c : parts) open.push(splitA ? Pair{bound(c, p.cb), c, p.cb} : Pair{bound(p.ca, c), p.ca, c});
  }
  return !open.empty() && open.top().bound > margin;
}

/// Whether the pair is worth the proof above: curved or meshed models whose global query can be slow (convex
/// pairs have fast exact routines), never a point cloud (its points may sit inside a solid with no surface near
/// them), and with no sample of either surface inside the other solid (surfaces apart, one inside the other).
bool apartWithoutQuery(const Model& a, const Eigen::Isometry3d& X_WA, const Model& b, const Eigen::Isometry3d& X_WB,
                       double margin) {
  if (a.isConvex() && b.isConvex()) return false;
  if (a.type() == ModelType::PointCloud || b.type() == ModelType::PointCloud) return false;
  if (!provablyApart(a, X_WA, b, X_WB, margin)) return false;
  const Eigen::Isometry3d X_AB = X_WA.inverse() * X_WB;
  for (const SurfaceCell& c : b.surfaceCells())
    if (a.inside(X_AB * c.sample)) return false;
  for (const SurfaceCell& c : a.surfaceCells())
    if (b.inside(X_AB.inverse() * c.sample)) return false;
  return true;
}

/// What moving a lifted contact back adds to its error bound. Translating A's point by s·n changes its distance
/// to B by exactly s·(n·n_c) along the contact normal n_c (the closest point stays put along that ray) and by at
/// most the tangential part s·|n × n_c| (distance is 1-Lipschitz); once the point is past B's surface
/// (distance < 0) the true depth lies between 0 and the reported one.
double liftError(double skin, const Eigen::Vector3d& n, const Contact& c) {
  return skin * n.cross(c.normal).norm() + std::max(0.0, -c.distance);
}

/// Whether contacts() works on the model as a mesh (a box becomes its 12-triangle stand-in).
bool meshLike(const Model& m) { return m.type() == ModelType::Box || m.type() == ModelType::Mesh; }

std::vector<Contact> globalContacts(const Model& a, const Eigen::Isometry3d& X_WA, const Model& b,
                                    const Eigen::Isometry3d& X_WB, double margin, const QueryOptions& dial, bool patch) {
  const double tol = dial.tolerance;
  if (a.type() == ModelType::Box && b.type() == ModelType::Box) {
    // Clipping gives the whole contact polygon with exact depths: no feature search, no patch to fill.
    std::vector<Contact> cs = contact::boxBoxContacts(static_cast<const Box&>(a), X_WA, static_cast<const Box&>(b),
                                                      X_WB, margin, tol, 0);
    contact::mergeDuplicates(cs, 4 * tol);
    return cs;
  }
  if (apartWithoutQuery(a, X_WA, b, X_WB, margin)) return {};
  ContactOptions co;
  static_cast<QueryOptions&>(co) = dial;
  co.margin = margin;
  std::vector<Contact> cs = contacts(a, X_WA, b, X_WB, co);
  // A global minimum within a coarse tolerance may sit far from the true one along a curved surface (√(2·r·tol)
  // on a ball of radius r): move every contact to its local minimum.
  const Eigen::Isometry3d X_AW = X_WA.inverse(), X_BW = X_WB.inverse();
  const DeepenSteps steps{kDeepenRounds, kDeepenSlackInTolerances * tol};
  for (Contact& c : cs) c = deepenBoth(c, a, X_WA, X_AW, b, X_WB, X_BW, steps);
  if (a.isConvex() && b.isConvex() && meshLike(a) && meshLike(b)) {
    // Two convex polytopes (boxes, convex meshes) go through the mesh feature search, which reports corners but
    // not the global answer: add it (exact minimum translation when they overlap), the contact a solver wants
    // first. Every other pair's contacts() already holds the global answer.
    DistanceOptions query;
    static_cast<QueryOptions&>(query) = dial;
    const DistanceResult d = distance(a, X_WA, b, X_WB, query);
    if (d.distance <= margin) {
      Contact c;
      c.pointA = d.pointA, c.pointB = d.pointB, c.normal = d.normal, c.distance = d.distance;
      c.errorBound = d.errorBound();
      c.featureA = a.closestPoint(X_WA.inverse() * c.pointA).feature;
      c.featureB = b.closestPoint(X_WB.inverse() * c.pointB).feature;
      cs.push_back(c);
      contact::mergeDuplicates(cs, 4 * tol);
    }
  }
  if (patch && !cs.empty() && cs.size() < 3) {
    // Tilt the smaller model: a large one's tilted support point is far from the contact (a floor's corner).
    if (b.localBoundingSphere().radius < a.localBoundingSphere().radius) {
      for (Contact& c : cs) c = swapped(c);
      fillPatch(b, X_WB, a, X_WA, margin, steps.slack, cs);
      for (Contact& c : cs) c = swapped(c);
    } else {
      fillPatch(a, X_WA, b, X_WB, margin, steps.slack, cs);
    }
    contact::mergeDuplicates(cs, 4 * tol);
  }
  return cs;
}

void checkOptions(const ManifoldOptions& o) {
  if (!std::isfinite(o.margin) || o.margin < 0) throw InputError("manifoldContacts: margin must be finite and >= 0");
  if (o.maxContacts <= 0) throw InputError("manifoldContacts: maxContacts must be > 0");
  if (std::isnan(o.tolerance) || o.tolerance == std::numeric_limits<double>::infinity())
    throw InputError("manifoldContacts: tolerance must be finite");
  if (const char* why = invalidDialSetting(o)) throw InputError(std::string("manifoldContacts: ") + why);
}

/// The contacts at one pose of A (the true one, or A lifted off B), through the cache when it holds.
std::vector<Contact> contactsAt(const Model& a, const Eigen::Isometry3d& X_WA, const Model& b,
                                const Eigen::Isometry3d& X_WB, double margin, const QueryOptions& dial, bool patch,
                                bool local, ContactCache* cache) {
  const double tol = dial.tolerance;
  const Eigen::Isometry3d X_AB = X_WA.inverse() * X_WB;
  std::vector<Contact> out;
  if (cache && cache->valid && relativeMotion(a, b, cache->X_AB, X_AB) <= cache->guard) {
    ++cache->localUpdates;
    contact::WarmProjections* projections = cache->projections.get();
    const UpdateFrames frames(X_WA, X_WB, cache->X_AB, kDeepenSlackInTolerances * tol, projections);
    for (const Contact& c : cache->contacts) {
      const Contact now = remeasure(c, a, b, frames);
      if (now.distance <= margin) out.push_back(now);
    }
    if (projections) {
      cache->localProjections = projections->work().steps + projections->work().newton;
      cache->projectionFallbacks = projections->work().fallbacks;
    }
    contact::mergeDuplicates(out, 4 * tol);
    return out;
  }
  if (!cache) return globalContacts(a, X_WA, b, X_WB, margin, dial, patch);
  // Search a margin grown by twice the guard: while the pair moves less than the guard, every point pair now
  // within the margin was within the grown margin then, so its region holds a cached local minimum.
  const double guard = kGuardInTolerances * tol;
  const std::vector<Contact> all = globalContacts(a, X_WA, b, X_WB, margin + 2 * guard, dial, patch);
  ++cache->globalSearches;
  cache->valid = true;
  cache->X_AB = X_AB;
  cache->guard = guard;
  cache->contacts.clear();
  const bool nurbsA = a.type() == ModelType::Nurbs, nurbsB = b.type() == ModelType::Nurbs;
  if (!local || !(nurbsA || nurbsB))
    cache->projections.reset();
  else if (!(cache->projections && cache->projections->serves(a, b)))
    cache->projections = std::make_shared<contact::WarmProjections>(a, b);
  const Eigen::Isometry3d X_AW = X_WA.inverse(), X_BW = X_WB.inverse();
  for (const Contact& c : all) {
    Contact local = c;
    local.pointA = X_AW * c.pointA;
    local.pointB = X_AW * c.pointB;
    local.normal = X_AW.linear() * c.normal;
    // A NURBS point's (u, v) is where the local projections start: read it exactly once per search (the
    // routines that found the contact may not have kept it).
    const auto place = [](const Model& m, const Eigen::Vector3d& p, int& feature, Eigen::Vector2d& param) {
      const SurfacePoint s = m.closestPoint(p);
      feature = s.feature, param = s.param;
    };
    if (nurbsA) place(a, local.pointA, local.featureA, local.paramA);
    if (nurbsB) place(b, X_BW * c.pointB, local.featureB, local.paramB);
    cache->contacts.push_back(local);
    if (c.distance <= margin) out.push_back(c);
  }
  return out;
}


std::vector<Contact> manifoldOfModels(const Model& a, const Eigen::Isometry3d& X_WA, const Model& b,
                                      const Eigen::Isometry3d& X_WB, const ManifoldOptions& options,
                                      ContactCache* cache) {
  if (!X_WA.matrix().allFinite() || !X_WB.matrix().allFinite())
    throw InputError("manifoldContacts: non-finite pose");
  const double tol = options.tolerance >= 0 ? options.tolerance : defaultSimulationTolerance(a, b);
  QueryOptions dial = options;  // the caller's dial with the tolerance settled
  dial.tolerance = tol;

  // Resting bodies sink a little into each other every step. Overlap is where contacts are expensive (a
  // global penetration search) and ill-posed (a box corner below an open floor has no inside to be in), so
  // when the last step's contact normal is known, A is lifted off B along it by a skin and the contacts of the
  // separated pair are measured and moved back: translating A by −s·n changes a contact's gap along its normal
  // n_c by exactly s·(n·n_c). If A still overlaps B after the lift, the true pose is used.
  std::vector<Contact> out;
  bool lifted = false;
  if (cache && cache->hasLift) {
    const double skin = std::max(options.margin, kSkinInTolerances * tol);
    const Eigen::Vector3d n = X_WB.linear() * cache->liftNormal_B;
    Eigen::Isometry3d X_WAl = X_WA;
    X_WAl.pretranslate(-skin * n);
    out = contactsAt(a, X_WAl, b, X_WB, options.margin + skin, dial, options.fillPatch, options.localWarmStart, cache);
    lifted = std::none_of(out.begin(), out.end(), [&](const Contact& c) { return c.distance < -tol; });
    if (lifted) {
      for (Contact& c : out) {
        // A's point is exact; B's is kept on B's tangent plane so that pointB − pointA = distance · normal still
        // holds when the lift and the contact normal differ (exactly B's point when they agree).
        c.pointA += skin * n;
        c.distance -= skin * n.dot(c.normal);
        c.pointB = c.pointA + c.distance * c.normal;
        c.errorBound += liftError(skin, n, c);
      }
      out.erase(std::remove_if(out.begin(), out.end(), [&](const Contact& c) { return c.distance > options.margin; }),
                out.end());
    } else {
      cache->valid = false;  // its contacts belong to the lifted pose
    }
  }
  if (!lifted) out = contactsAt(a, X_WA, b, X_WB, options.margin, dial, options.fillPatch, options.localWarmStart, cache);
  contact::mergeDuplicates(out, 4 * tol);
  if (cache) {
    // The next step lifts along this step's deepest normal (kept in B's frame: a ball rolling on a floor turns,
    // the floor's normal does not). A cache whose lift direction changes starts a new global search.
    const bool had = cache->hasLift;
    const Eigen::Vector3d before = cache->liftNormal_B;
    cache->hasLift = !out.empty();
    if (cache->hasLift) cache->liftNormal_B = X_WB.linear().transpose() * out.front().normal;
    if (had != cache->hasLift || (had && before.dot(cache->liftNormal_B) < 1 - 1e-6)) cache->valid = false;
  }
  contact::reduceContacts(out, options.maxContacts);
  for (Contact& c : out) c.errorBound += contact::roundingBound(c);
  return out;
}

}  // namespace

std::vector<Contact> manifoldContacts(const Model& a, const Eigen::Isometry3d& X_WA, const Model& b,
                                      const Eigen::Isometry3d& X_WB, const ManifoldOptions& options,
                                      ContactCache* cache) {
  checkOptions(options);
  // At a level of detail the contacts are the stand-ins' (the same stand-in every step: the cache stays valid).
  ManifoldOptions exact = options;
  exact.detailA = exact.detailB = 0;
  const StandIn sa = a.atDetail(options.detailA), sb = b.atDetail(options.detailB);
  std::vector<Contact> out = manifoldOfModels(*sa.model, X_WA, *sb.model, X_WB, exact, cache);
  for (Contact& c : out) c.errorBound += sa.deviation + sb.deviation;
  return out;
}

}  // namespace unidist
