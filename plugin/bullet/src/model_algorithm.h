// The plugin's collision algorithm: one per broadphase pair (kept by Bullet while the pair overlaps) or per
// closest-point query. Reads both poses from the wrappers each step, asks the core for the pair's contacts
// (with the pair's warm-start cache) and writes them into the manifold in Bullet's conventions. Internal.
#pragma once

#include "registration.h"

#include <BulletCollision/CollisionDispatch/btActivatingCollisionAlgorithm.h>

#include <memory>
#include <string>

namespace unidist::bullet {

struct PairState;

class ModelAlgorithm final : public btActivatingCollisionAlgorithm {
 public:
  /// `swapped`: body 1 of the dispatch is the unidist shape (the reverse table cells).
  ModelAlgorithm(btPersistentManifold* manifold, const btCollisionAlgorithmConstructionInfo& ci,
                 const btCollisionObjectWrapper* w0, const btCollisionObjectWrapper* w1, bool swapped,
                 Registration::Impl* registration);
  ~ModelAlgorithm() override;

  void processCollision(const btCollisionObjectWrapper* w0, const btCollisionObjectWrapper* w1,
                        const btDispatcherInfo& info, btManifoldResult* result) override;
  /// Only for DISPATCH_CONTINUOUS, which btDiscreteDynamicsWorld never sets: tunnelling is prevented by
  /// speculative contacts instead.
  btScalar calculateTimeOfImpact(btCollisionObject*, btCollisionObject*, const btDispatcherInfo&,
                                 btManifoldResult*) override {
    return 1;
  }
  void getAllContactManifolds(btManifoldArray& manifolds) override;

  struct CreateFunc final : btCollisionAlgorithmCreateFunc {
    CreateFunc(bool swapped, Registration::Impl* registration) : registration_(registration) { m_swapped = swapped; }
    btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
                                                   const btCollisionObjectWrapper* w0,
                                                   const btCollisionObjectWrapper* w1) override;

   private:
    Registration::Impl* registration_;
  };

 private:
  /// processCollision's work; it may throw (processCollision catches: nothing may unwind through Bullet).
  void collide(const btCollisionObjectWrapper* w0, const btCollisionObjectWrapper* w1, const btDispatcherInfo& info,
               btManifoldResult* result);
  /// No contacts for this pair this step, counted in stats().skippedPairs.
  void skipPair(const std::string& why);
  /// Empties the own manifold and the extra ones (a pair with no contacts this step leaves no ghost points).
  void clearOwnManifolds();

  btPersistentManifold* manifold_;
  bool ownManifold_ = false;
  bool swapped_;
  btScalar baseThreshold_ = 0;  // the own manifold's threshold before any speculative growth
  Registration::Impl* registration_;
  std::unique_ptr<PairState> state_;
};

}  // namespace unidist::bullet
