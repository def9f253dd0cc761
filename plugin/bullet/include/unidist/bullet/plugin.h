// Registering unidist with a Bullet dispatcher: one call installs the plugin's collision algorithm for every
// pair of (unidist shape) × (unidist shape or any Bullet shape a scene can hold), in both argument orders and
// in both dispatch tables (simulation contacts, used by stepSimulation; closest points, used by contactTest,
// contactPairTest). Compound cells are left to Bullet, which recurses into the children.
//
//   btDefaultCollisionConfiguration config;
//   btCollisionDispatcher dispatcher(&config);
//   auto unidistPlugin = unidist::bullet::registerAlgorithms(&dispatcher);  // after GImpact's registration
//   ... world, bodies with unidist::bullet::makeShape(model) ...
//   // teardown: the world first, then unidistPlugin (restores the dispatcher's defaults), then the dispatcher
//
// Contacts come from unidist::manifoldContacts (core): the local minima of distance within the manifold's
// contact threshold plus a speculative distance (relative speed × time step, so fast bodies do not tunnel),
// a resting patch filled in, at most four per manifold (deepest and most spread), with a warm-start cache per
// pair. Conventions (verified against Bullet's own sphere–sphere and box–box): the manifold's normal points
// from body 1 to body 0, distance < 0 penetrates, Bullet's outside margins (btConvexHullShape) are honoured.
#pragma once

#include <btBulletCollisionCommon.h>

#include <memory>
#include <string>

namespace unidist::bullet {

/// What registerAlgorithms() returns: owns the algorithm factories and a cache of converted Bullet meshes.
class Registration {
 public:
  explicit Registration(btCollisionDispatcher* dispatcher);
  ~Registration();  ///< restores the configuration's defaults
  Registration(const Registration&) = delete;
  Registration& operator=(const Registration&) = delete;

  struct Impl;  // internal
  Impl& impl() { return *impl_; }
  const Impl& impl() const { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

/// Installs the algorithm in every cell of both tables that a unidist shape type takes part in (both orders),
/// except compound cells. Call after btGImpactCollisionAlgorithm::registerAlgorithm when GImpact is used (it
/// overwrites its whole row). The returned object owns the algorithm factories and a cache of converted Bullet
/// meshes; keep it alive while the dispatcher is used, and destroy it after the world: destroying it puts the
/// configuration's default factories back in every cell it wrote — so on one dispatcher, destroy an old
/// registration before making a new one.
std::unique_ptr<Registration> registerAlgorithms(btCollisionDispatcher* dispatcher);

/// Restores the configuration's defaults in every cell the registration wrote (also done by its destructor).
void unregisterAlgorithms(Registration& registration);

/// Counters for tests and benchmarks: how many global contact searches and warm-start local updates the
/// registration's algorithms have run, and how many times a pair was skipped for one step — no contacts, nothing
/// thrown through Bullet — because a pose or velocity was not finite or its query failed (lastError says why).
struct PluginStats {
  long globalSearches = 0;
  long localUpdates = 0;
  long skippedPairs = 0;
  std::string lastError;
};
PluginStats stats(const Registration& registration);

}  // namespace unidist::bullet
