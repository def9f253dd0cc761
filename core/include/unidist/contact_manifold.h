// Contacts for rigid-body simulation, engine-neutral: what the Bullet algorithm and the ODE collider report
// each step. Built on unidist::contacts() (local minima of distance) and adds what a solver needs:
//  * a contact patch, not a point, where two curved or flat surfaces rest on each other along a curve or an area
//    (a torus on a table, a cylinder on its cap): when fewer than three contacts come back, A is tilted by a
//    small angle about two axes through the deepest contact, the deepest point of each tilted pose is mapped
//    back onto A's surface and kept when it is a contact of the untilted pair (its distance re-measured);
//  * at most maxContacts, keeping the deepest and the most spread;
//  * every contact's points on their local minimum: each moved to its model's local support point along the
//    contact normal (an offset along a curved surface is a lever a solver turns into a rolling torque);
//  * a warm start (ContactCache): while the relative pose of the pair has moved less than a guard distance
//    since the last global search, the cached contacts are updated locally (closest-point projections from the
//    last witness points — on NURBS the tracker's point Newton from each contact's (u, v), checked and backed by
//    the exact search — the normal of the search riding with B), which is sound because the global search was
//    run with the margin grown by that guard: no contact within the margin can appear that it did not see;
//  * a skin: once a pair has touched, A is lifted off B along the last contact normal before measuring, and
//    the contacts are moved back (exact for a translation), so resting overlaps are measured as separations —
//    cheap, and well defined also against open surfaces and point clouds, which have no inside.
// Conventions are unidist::Contact's: pointB − pointA = distance · normal, normal A→B, distance < 0 overlaps.
#pragma once

#include "unidist/contacts.h"

#include <memory>
#include <vector>

namespace unidist {

/// The dial (QueryOptions) with a simulation's default: a negative tolerance means 1e-4 × the smaller bounding
/// diagonal of the pair (contacts need not be more exact than the solver that uses them).
struct ManifoldOptions : QueryOptions {
  double margin = 0;      ///< report contacts with distance <= margin (>= 0): the engine's contact threshold
  int maxContacts = 4;    ///< > 0
  bool fillPatch = true;  ///< tilt A to find the rest of a resting patch (see above)
  /// The warm start projects NURBS points locally (the tracker's point Newton from each contact's (u, v));
  /// false: the exact global search every time (slower; for comparison and for suspect models).
  bool localWarmStart = true;
};

namespace contact {
class WarmProjections;
}

/// Per-pair state of the warm start. Owned by the engine's pair object (one per colliding pair); not shared
/// between threads. A default-constructed cache is empty; reset() forgets everything.
struct ContactCache {
  bool valid = false;
  Eigen::Isometry3d X_AB = Eigen::Isometry3d::Identity();  ///< relative pose at the last global search
  double guard = 0;                                        ///< motion allowed before the next global search
  std::vector<Contact> contacts;                           ///< in A's frame (pointB, normal included)
  bool hasLift = false;                                    ///< the last step had contacts:
  Eigen::Vector3d liftNormal_B = Eigen::Vector3d::UnitZ(); ///< its deepest normal, in B's frame
  long globalSearches = 0, localUpdates = 0;               ///< counters, for tests and benchmarks
  /// The local projections of the warm start (NURBS models: the tracker's point Newton from each contact's
  /// (u, v)), made at the first global search; internal. Their work so far: steps and Newton iterations, and
  /// how many fell back to the exact search.
  std::shared_ptr<contact::WarmProjections> projections;
  long localProjections = 0, projectionFallbacks = 0;
  void reset() { *this = ContactCache{}; }
};

/// Simulation contacts of a against b (poses in the world), deepest first. With a cache the result is the
/// same set of contacts up to the tolerance, at the cost of a local update while the pair rests.
std::vector<Contact> manifoldContacts(const Model& a, const Eigen::Isometry3d& X_WA, const Model& b,
                                      const Eigen::Isometry3d& X_WB, const ManifoldOptions& options,
                                      ContactCache* cache = nullptr);

}  // namespace unidist
