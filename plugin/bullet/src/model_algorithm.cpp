#include "model_algorithm.h"

#include "aabb_gap.h"
#include "eigen_bullet.h"
#include "regions.h"
#include "unidist/bullet/shapes.h"
#include "unidist/contact_manifold.h"

#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <utility>

namespace unidist::bullet {

/// What a pair keeps between steps.
struct PairState {
  ContactCache cache;
  std::vector<btPersistentManifold*> extra;  // own manifolds beyond the first, one per further contact region
  const Model* cachedA = nullptr;  // the cache belongs to these two models
  const Model* cachedB = nullptr;
};

namespace {

/// Manifolds per pair: Bullet keeps 4 points in each.
constexpr int kMaxRegions = 4;

/// The other side as a core model: a unidist shape's own model, a triangle converted afresh (Bullet reuses
/// one btTriangleShape object for every triangle it visits), anything else from the shared cache.
ConvertedShape otherModel(const btCollisionShape& shape, const ModelShapeData* data, Registration::Impl& registration) {
  if (data) return ConvertedShape{data->model(), 0, Eigen::Isometry3d::Identity()};
  if (shape.getShapeType() == TRIANGLE_SHAPE_PROXYTYPE) return modelFromBulletShape(shape);
  return registration.shapeCache.get(shape);
}

/// Distance from the shape's origin to its farthest point: a unidist model's own bounding ball (data: the shape's
/// unidist data, null for Bullet's shapes, whose getBoundingSphere goes through getAabb: six support queries).
double reach(const btCollisionShape& shape, const ModelShapeData* data) {
  if (data) {
    const BoundingSphere s = data->model()->localBoundingSphere();
    return s.center.norm() + s.radius;
  }
  btVector3 center;
  btScalar radius;
  shape.getBoundingSphere(center, radius);
  return double(center.length()) + double(radius);
}

/// How far the two objects can approach each other during the next step (relative speed bound × dt): contacts
/// up to that distance are reported as speculative ones so that a fast body meets the solver before it tunnels.
double speculativeDistance(const btCollisionObjectWrapper* a, const ModelShapeData* da,
                           const btCollisionObjectWrapper* b, const ModelShapeData* db, double dt) {
  double speed = 0;
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  for (const auto& [w, data] : {std::pair{a, da}, std::pair{b, db}}) {
    const btRigidBody* body = btRigidBody::upcast(w->getCollisionObject());
    if (!body) continue;
    const Eigen::Vector3d lin = toEigen(body->getLinearVelocity());
    v += (w == a) ? lin : Eigen::Vector3d(-lin);
    const double spin = toEigen(body->getAngularVelocity()).norm();
    if (spin != 0) speed += spin * reach(*w->getCollisionShape(), data);  // != 0: a NaN spin must show
  }
  return (v.norm() + speed) * dt;
}

/// What manifoldContacts does to the cache of a pair without contacts: no lift next step, and the last search
/// (made lifted) is not reused.
void forgetLift(ContactCache& cache) {
  if (!cache.hasLift) return;
  cache.hasLift = false;
  cache.valid = false;
}

bool finitePose(const btCollisionObjectWrapper& w) { return toEigen(w.getWorldTransform()).matrix().allFinite(); }

/// b: the other shape's unidist data, null for Bullet's shapes.
QueryOptions pairDial(const ModelShapeData& a, const ModelShapeData* b) {
  return dialOfPair(a.queryOptions(), b ? &b->queryOptions() : nullptr);
}

}  // namespace

ModelAlgorithm::ModelAlgorithm(btPersistentManifold* manifold, const btCollisionAlgorithmConstructionInfo& ci,
                               const btCollisionObjectWrapper* w0, const btCollisionObjectWrapper* w1, bool swapped,
                               Registration::Impl* registration)
    : btActivatingCollisionAlgorithm(ci, w0, w1),
      manifold_(manifold),
      swapped_(swapped),
      registration_(registration),
      state_(std::make_unique<PairState>()) {
  if (!manifold_) {  // own manifold, ordered (unidist shape, other); wrapper transforms are not valid yet
    const btCollisionObjectWrapper* a = swapped ? w1 : w0;
    const btCollisionObjectWrapper* b = swapped ? w0 : w1;
    manifold_ = m_dispatcher->getNewManifold(a->getCollisionObject(), b->getCollisionObject());
    ownManifold_ = true;
    baseThreshold_ = manifold_->getContactBreakingThreshold();
  }
}

ModelAlgorithm::~ModelAlgorithm() {
  if (ownManifold_ && manifold_) m_dispatcher->releaseManifold(manifold_);
  for (btPersistentManifold* m : state_->extra) m_dispatcher->releaseManifold(m);
}

namespace {

/// Where a manifold's points are (world, on body 1); none when it is empty.
bool manifoldCentre(const btPersistentManifold& m, Eigen::Vector3d& centre) {
  if (m.getNumContacts() == 0) return false;
  centre.setZero();
  for (int i = 0; i < m.getNumContacts(); ++i) centre += toEigen(m.getContactPoint(i).getPositionWorldOnB());
  centre /= m.getNumContacts();
  return true;
}

Eigen::Vector3d regionCentre(const std::vector<Contact>& region) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const Contact& k : region) c += 0.5 * (k.pointA + k.pointB);
  return c / double(region.size());
}

}  // namespace

void ModelAlgorithm::processCollision(const btCollisionObjectWrapper* w0, const btCollisionObjectWrapper* w1,
                                      const btDispatcherInfo& info, btManifoldResult* result) {
  // An exception unwinding through Bullet's dispatch would leave the world half-stepped: the pair is skipped.
  try {
    collide(w0, w1, info, result);
  } catch (const std::exception& e) {
    skipPair(e.what());
  } catch (...) {
    skipPair("unknown exception");
  }
}

void ModelAlgorithm::skipPair(const std::string& why) {
  state_->cache.reset();
  if (ownManifold_) {
    manifold_->setContactBreakingThreshold(baseThreshold_);
    clearOwnManifolds();
  }
  registration_->noteSkip("unidist Bullet algorithm: pair skipped: " + why);
}

void ModelAlgorithm::collide(const btCollisionObjectWrapper* w0, const btCollisionObjectWrapper* w1,
                             const btDispatcherInfo& info, btManifoldResult* result) {
  const btCollisionObjectWrapper* a = swapped_ ? w1 : w0;  // the unidist shape
  const btCollisionObjectWrapper* b = swapped_ ? w0 : w1;
  const ModelShapeData* da = shapeData(a->getCollisionShape());
  if (!da) return;  // a table cell reached with a shape that is not ours: nothing to say about it
  const ModelShapeData* db = shapeData(b->getCollisionShape());  // once: the lookups below would each cast again
  const ConvertedShape other = otherModel(*b->getCollisionShape(), db, *registration_);
  const Model& modelA = *da->model();
  const Model& modelB = *other.model;
  if (state_->cachedA != &modelA || state_->cachedB != &modelB) {
    state_->cache.reset();
    state_->cachedA = &modelA;
    state_->cachedB = &modelB;
  }

  result->setPersistentManifold(manifold_);  // before any addContactPoint (closest-point queries need it too)
  const double speculative = speculativeDistance(a, da, b, db, double(info.m_timeStep));
  if (!std::isfinite(speculative) || !finitePose(*a) || !finitePose(*b)) {  // a body blew up: its motion means nothing
    skipPair("non-finite pose or velocity");
    return;
  }
  double threshold = double(manifold_->getContactBreakingThreshold());
  if (ownManifold_) {
    threshold = double(baseThreshold_) + speculative;
    manifold_->setContactBreakingThreshold(btScalar(threshold));
  }
  ManifoldOptions options;
  static_cast<QueryOptions&>(options) = pairDial(*da, db);
  options.margin = threshold + double(result->m_closestPointDistanceThreshold) + other.outerMargin;
  options.maxContacts = ownManifold_ ? 4 * kMaxRegions : 4;
  if (aabbGap(*a, *b) > options.margin) {  // most pairs the broadphase hands over: proved apart, no query
    forgetLift(state_->cache);
    if (ownManifold_) clearOwnManifolds();
    return;
  }

  const long globalBefore = state_->cache.globalSearches, localBefore = state_->cache.localUpdates;
  // A Bullet capsule, cylinder or cone along x or y is a unidist one along z posed by X_SM.
  const std::vector<Contact> cs = manifoldContacts(modelA, toEigen(a->getWorldTransform()), modelB,
                                                   toEigen(b->getWorldTransform()) * other.X_SM, options,
                                                   &state_->cache);
  registration_->globalSearches += state_->cache.globalSearches - globalBefore;
  registration_->localUpdates += state_->cache.localUpdates - localBefore;
  const bool aIsBody0 = manifold_->getBody0() == a->getCollisionObject();
  auto add = [&](const Contact& c) {
    // B's surface grows by Bullet's outside margin: the gap shrinks by it and B's point moves toward A.
    const double d = c.distance - other.outerMargin;
    const Eigen::Vector3d pointB = c.pointB - other.outerMargin * c.normal;
    if (aIsBody0)  // manifold (unidist, other): normal on B (other) pointing at A, the point on B
      result->addContactPoint(toBullet(Eigen::Vector3d(-c.normal)), toBullet(pointB), btScalar(d));
    else  // shared manifold ordered (other, unidist): normal on the unidist shape pointing at the other
      result->addContactPoint(toBullet(c.normal), toBullet(c.pointA), btScalar(d));
  };
  if (!ownManifold_) {  // a compound's or a mesh's shared manifold: four points, its owner refreshes
    for (const Contact& c : cs) add(c);
    return;
  }
  if (cs.empty()) {  // most pairs the broadphase hands over: no regions to match, nothing to allocate
    clearOwnManifolds();
    return;
  }
  if (cs.size() <= 4 && state_->extra.empty()) {  // one region, and the own manifold is the only one to hold it
    for (const Contact& c : cs) add(c);
    result->refreshContactPoints();
    return;
  }
  // One manifold per contact region (a non-convex pair touching in separate places), each matched to the
  // manifold that held the nearest points last step so that Bullet's warm starting carries over.
  const std::vector<std::vector<Contact>> regions = contactRegions(cs, kMaxRegions);
  std::vector<btPersistentManifold*> pool = {manifold_};
  pool.insert(pool.end(), state_->extra.begin(), state_->extra.end());
  while (pool.size() < regions.size()) {
    btPersistentManifold* m = m_dispatcher->getNewManifold(manifold_->getBody0(), manifold_->getBody1());
    state_->extra.push_back(m);
    pool.push_back(m);
  }
  std::vector<char> used(pool.size(), 0);
  for (const std::vector<Contact>& region : regions) {
    const Eigen::Vector3d centre = regionCentre(region);
    std::size_t best = pool.size();
    double bestDistance = std::numeric_limits<double>::infinity();
    for (std::size_t m = 0; m < pool.size(); ++m) {
      if (used[m]) continue;
      Eigen::Vector3d c;
      const double dist = manifoldCentre(*pool[m], c) ? (c - centre).norm() : 1e300;
      if (best == pool.size() || dist < bestDistance) best = m, bestDistance = dist;
    }
    used[best] = 1;
    pool[best]->setContactBreakingThreshold(btScalar(threshold));
    result->setPersistentManifold(pool[best]);
    for (const Contact& c : region) add(c);
    result->refreshContactPoints();
  }
  for (std::size_t m = 0; m < pool.size(); ++m)
    if (!used[m]) pool[m]->clearManifold();  // a region that is gone leaves no ghost points
  result->setPersistentManifold(manifold_);
}

void ModelAlgorithm::clearOwnManifolds() {
  if (manifold_->getNumContacts() > 0) manifold_->clearManifold();
  for (btPersistentManifold* m : state_->extra)
    if (m->getNumContacts() > 0) m->clearManifold();
}

void ModelAlgorithm::getAllContactManifolds(btManifoldArray& manifolds) {
  if (!ownManifold_ || !manifold_) return;
  manifolds.push_back(manifold_);
  for (btPersistentManifold* m : state_->extra) manifolds.push_back(m);
}

btCollisionAlgorithm* ModelAlgorithm::CreateFunc::CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
                                                                           const btCollisionObjectWrapper* w0,
                                                                           const btCollisionObjectWrapper* w1) {
  void* memory = ci.m_dispatcher1->allocateCollisionAlgorithm(sizeof(ModelAlgorithm));
  return new (memory) ModelAlgorithm(ci.m_manifold, ci, w0, w1, m_swapped, registration_);
}

}  // namespace unidist::bullet
