#include "registration.h"

#include "model_algorithm.h"

#include <BulletCollision/BroadphaseCollision/btBroadphaseProxy.h>

namespace unidist::bullet {
namespace {

/// Enough of a shape to notice that the object at an address is not the one converted.
std::vector<double> fingerprint(const btCollisionShape& shape) {
  btVector3 mn, mx;
  shape.getAabb(btTransform::getIdentity(), mn, mx);
  const btVector3 s = shape.getLocalScaling();
  return {double(shape.getShapeType()), double(shape.getMargin()), double(mn.x()), double(mn.y()), double(mn.z()),
          double(mx.x()), double(mx.y()), double(mx.z()), double(s.x()), double(s.y()), double(s.z())};
}

bool isUnidistType(int t) { return t == CUSTOM_CONVEX_SHAPE_TYPE || t == CUSTOM_CONCAVE_SHAPE_TYPE; }

}  // namespace

ConvertedShape ShapeModelCache::get(const btCollisionShape& shape) {
  const std::vector<double> print = fingerprint(shape);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto found = entries_.find(&shape);
    if (found != entries_.end() && found->second.fingerprint == print) return found->second.converted;
  }
  ConvertedShape converted = modelFromBulletShape(shape);  // outside the lock: a big mesh takes a while
  std::lock_guard<std::mutex> lock(mutex_);
  entries_[&shape] = Entry{print, converted};
  return converted;
}

Registration::Impl::Impl(btCollisionDispatcher* d)
    : dispatcher(d),
      forward(std::make_unique<ModelAlgorithm::CreateFunc>(false, this)),
      reverse(std::make_unique<ModelAlgorithm::CreateFunc>(true, this)) {
  if (!dispatcher) throw InputError("unidist::bullet::registerAlgorithms: null dispatcher");
  // Every cell of the unidist types' rows and columns except compounds (Bullet recurses into the children and
  // looks up [child][other]). CUSTOM_CONCAVE_SHAPE_TYPE is also SDF_SHAPE_PROXYTYPE: an unregistered cell would
  // send a unidist shape into Bullet's SDF algorithm, which casts it and crashes, so no cell is left out.
  for (int mine : {int(CUSTOM_CONVEX_SHAPE_TYPE), int(CUSTOM_CONCAVE_SHAPE_TYPE)}) {
    for (int other = 0; other < MAX_BROADPHASE_COLLISION_TYPES; ++other) {
      if (other == COMPOUND_SHAPE_PROXYTYPE) continue;
      cells.emplace_back(mine, other);
      if (!isUnidistType(other)) cells.emplace_back(other, mine);
    }
  }
  for (const auto& [t0, t1] : cells) {
    btCollisionAlgorithmCreateFunc* f = isUnidistType(t0) ? forward.get() : reverse.get();
    dispatcher->registerCollisionCreateFunc(t0, t1, f);
    dispatcher->registerClosestPointsCreateFunc(t0, t1, f);
  }
}

void Registration::Impl::restoreDefaults() {
  btCollisionConfiguration* config = dispatcher->getCollisionConfiguration();
  for (const auto& [t0, t1] : cells) {
    dispatcher->registerCollisionCreateFunc(t0, t1, config->getCollisionAlgorithmCreateFunc(t0, t1));
    dispatcher->registerClosestPointsCreateFunc(t0, t1, config->getClosestPointsAlgorithmCreateFunc(t0, t1));
  }
  cells.clear();
}

Registration::Registration(btCollisionDispatcher* dispatcher) : impl_(std::make_unique<Impl>(dispatcher)) {}

Registration::~Registration() { impl_->restoreDefaults(); }

std::unique_ptr<Registration> registerAlgorithms(btCollisionDispatcher* dispatcher) {
  return std::make_unique<Registration>(dispatcher);
}

void unregisterAlgorithms(Registration& registration) { registration.impl().restoreDefaults(); }

void Registration::Impl::noteSkip(const std::string& why) {
  ++skippedPairs;
  std::lock_guard<std::mutex> lock(errorMutex);
  lastError = why;
}

PluginStats stats(const Registration& registration) {
  const Registration::Impl& r = registration.impl();
  std::lock_guard<std::mutex> lock(r.errorMutex);
  return PluginStats{r.globalSearches.load(), r.localUpdates.load(), r.skippedPairs.load(), r.lastError};
}

}  // namespace unidist::bullet
