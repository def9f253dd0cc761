// The compound–compound algorithm of unidist/bullet/raster_compounds.h: both compounds as unions of convex pieces
// (cached), unidist::raster::unionDistance on the registration's one off-screen context, one contact per step in
// Bullet's conventions (normal on body 1 pointing at body 0, the point on body 1, distance < 0 penetrates).
#include "unidist/bullet/raster_compounds.h"

#include "aabb_gap.h"
#include "eigen_bullet.h"
#include "unidist/adapters/bullet_compounds.h"
#include "unidist/raster/convex_piece.h"

#include <BulletCollision/CollisionDispatch/btActivatingCollisionAlgorithm.h>
#include <BulletCollision/CollisionShapes/btCompoundShape.h>

#include <mutex>
#include <unordered_map>

namespace unidist::bullet {
namespace {

/// A compound as convex pieces, or why it cannot be one.
struct ConvertedCompound {
  std::vector<double> fingerprint;
  std::shared_ptr<const raster::ConvexUnion> pieces;  // null when the compound is not a union of convex children
  double outerMargin = 0;
  double diagonal = 0;
  std::string error;
};

std::vector<double> fingerprint(const btCompoundShape& shape) {
  btVector3 mn, mx;
  shape.getAabb(btTransform::getIdentity(), mn, mx);
  return {double(shape.getNumChildShapes()), double(mn.x()), double(mn.y()), double(mn.z()),
          double(mx.x()),                    double(mx.y()), double(mx.z())};
}

ConvertedCompound convert(const btCompoundShape& shape) {
  ConvertedCompound out;
  out.fingerprint = fingerprint(shape);
  try {
    const CompoundPieces source = convexPiecesOfCompound(shape);
    auto pieces = std::make_shared<raster::ConvexUnion>();
    Aabb box;
    for (std::size_t i = 0; i < source.pieces.size(); ++i) {
      pieces->push_back(raster::convexPiece(source.pieces[i], {}, "child " + std::to_string(i)));
      for (const Eigen::Vector3d& p : source.pieces[i]) box.extend(p);
    }
    out.pieces = std::move(pieces);
    out.outerMargin = source.outerMargin;
    out.diagonal = box.diagonal();
  } catch (const InputError& e) {
    out.error = e.what();
  }
  return out;
}

}  // namespace

struct RasterCompoundRegistration::Impl {
  Impl(btCollisionDispatcher* d, const RasterCompoundOptions& o);
  void restoreDefaults();
  ConvertedCompound compound(const btCompoundShape& shape);
  void recordFallback(const std::string& why);

  btCollisionDispatcher* dispatcher;
  RasterCompoundOptions options;
  btCollisionAlgorithmCreateFunc* defaultCollision;
  btCollisionAlgorithmCreateFunc* defaultClosest;
  std::unique_ptr<btCollisionAlgorithmCreateFunc> createFunc;
  bool registered = false;

  std::mutex cacheMutex;
  std::unordered_map<const btCollisionShape*, ConvertedCompound> cache;

  std::mutex contextMutex;  // one query at a time on the context
  std::unique_ptr<raster::OffscreenContext> context;

  std::mutex statsMutex;
  RasterCompoundStats stats;
};

namespace {

class RasterCompoundAlgorithm final : public btActivatingCollisionAlgorithm {
 public:
  RasterCompoundAlgorithm(const btCollisionAlgorithmConstructionInfo& ci, const btCollisionObjectWrapper* w0,
                          const btCollisionObjectWrapper* w1, RasterCompoundRegistration::Impl* registration)
      : btActivatingCollisionAlgorithm(ci, w0, w1), registration_(registration) {
    manifold_ = m_dispatcher->getNewManifold(w0->getCollisionObject(), w1->getCollisionObject());
  }
  ~RasterCompoundAlgorithm() override { m_dispatcher->releaseManifold(manifold_); }

  void processCollision(const btCollisionObjectWrapper* w0, const btCollisionObjectWrapper* w1,
                        const btDispatcherInfo&, btManifoldResult* result) override {
    result->setPersistentManifold(manifold_);
    const double threshold = double(manifold_->getContactBreakingThreshold()) +
                             double(result->m_closestPointDistanceThreshold);
    const ConvertedCompound a = registration_->compound(static_cast<const btCompoundShape&>(*w0->getCollisionShape()));
    const ConvertedCompound b = registration_->compound(static_cast<const btCompoundShape&>(*w1->getCollisionShape()));
    if (!a.pieces || !b.pieces || aabbGap(*w0, *w1) > threshold + a.outerMargin + b.outerMargin) {
      if (manifold_->getNumContacts() > 0) manifold_->clearManifold();
      return;
    }
    raster::UnionDistanceOptions options;
    options.resolution = registration_->options.resolution;
    options.tolerance = registration_->options.tolerance >= 0 ? registration_->options.tolerance
                                                              : 1e-4 * std::min(a.diagonal, b.diagonal);
    DistanceResult r;
    try {
      std::lock_guard<std::mutex> lock(registration_->contextMutex);
      if (!registration_->context)  // built on the first pair that needs it, once
        registration_->context = std::make_unique<raster::OffscreenContext>(options.resolution, options.resolution);
      r = raster::unionDistance(*registration_->context, *a.pieces, toEigen(w0->getWorldTransform()), *b.pieces,
                                toEigen(w1->getWorldTransform()), options);
    } catch (const std::exception& e) {  // never through Bullet's step: the pair gets no contact this step
      registration_->recordFallback(e.what());
      return;
    }
    {
      std::lock_guard<std::mutex> lock(registration_->statsMutex);
      ++registration_->stats.queries;
      registration_->stats.penetrating += r.distance < 0;
    }
    // Both surfaces grow by their outside margins: the gap shrinks by both, B's point moves toward A.
    const double d = r.distance - a.outerMargin - b.outerMargin;
    if (d > threshold) {
      if (manifold_->getNumContacts() > 0) manifold_->clearManifold();
      return;
    }
    const Eigen::Vector3d pointB = r.pointB - b.outerMargin * r.normal;
    result->addContactPoint(toBullet(Eigen::Vector3d(-r.normal)), toBullet(pointB), btScalar(d));
    result->refreshContactPoints();
  }

  btScalar calculateTimeOfImpact(btCollisionObject*, btCollisionObject*, const btDispatcherInfo&,
                                 btManifoldResult*) override {
    return 1;
  }
  void getAllContactManifolds(btManifoldArray& manifolds) override { manifolds.push_back(manifold_); }

 private:
  RasterCompoundRegistration::Impl* registration_;
  btPersistentManifold* manifold_;
};

/// Creates the image-space algorithm for two convertible compounds, Bullet's own otherwise.
struct CreateFunc final : btCollisionAlgorithmCreateFunc {
  CreateFunc(RasterCompoundRegistration::Impl* registration) : registration_(registration) {}
  btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
                                                 const btCollisionObjectWrapper* w0,
                                                 const btCollisionObjectWrapper* w1) override {
    const ConvertedCompound a = registration_->compound(static_cast<const btCompoundShape&>(*w0->getCollisionShape()));
    const ConvertedCompound b = registration_->compound(static_cast<const btCompoundShape&>(*w1->getCollisionShape()));
    if (!a.pieces || !b.pieces) {
      registration_->recordFallback(a.pieces ? b.error : a.error);
      // The closest-points table passes a null manifold; Bullet's compound algorithms serve both tables alike.
      return registration_->defaultCollision->CreateCollisionAlgorithm(ci, w0, w1);
    }
    void* memory = ci.m_dispatcher1->allocateCollisionAlgorithm(sizeof(RasterCompoundAlgorithm));
    return new (memory) RasterCompoundAlgorithm(ci, w0, w1, registration_);
  }

 private:
  RasterCompoundRegistration::Impl* registration_;
};

}  // namespace

RasterCompoundRegistration::Impl::Impl(btCollisionDispatcher* d, const RasterCompoundOptions& o)
    : dispatcher(d), options(o) {
  if (!dispatcher) throw InputError("unidist::bullet::registerRasterCompounds: null dispatcher");
  if (options.resolution < 8 || options.resolution > 4096)
    throw InputError("unidist::bullet::registerRasterCompounds: resolution must be 8..4096 (got " +
                     std::to_string(options.resolution) + ")");
  btCollisionConfiguration* config = dispatcher->getCollisionConfiguration();
  defaultCollision = config->getCollisionAlgorithmCreateFunc(COMPOUND_SHAPE_PROXYTYPE, COMPOUND_SHAPE_PROXYTYPE);
  defaultClosest = config->getClosestPointsAlgorithmCreateFunc(COMPOUND_SHAPE_PROXYTYPE, COMPOUND_SHAPE_PROXYTYPE);
  createFunc = std::make_unique<CreateFunc>(this);
  dispatcher->registerCollisionCreateFunc(COMPOUND_SHAPE_PROXYTYPE, COMPOUND_SHAPE_PROXYTYPE, createFunc.get());
  dispatcher->registerClosestPointsCreateFunc(COMPOUND_SHAPE_PROXYTYPE, COMPOUND_SHAPE_PROXYTYPE, createFunc.get());
  registered = true;
}

void RasterCompoundRegistration::Impl::restoreDefaults() {
  if (!registered) return;
  dispatcher->registerCollisionCreateFunc(COMPOUND_SHAPE_PROXYTYPE, COMPOUND_SHAPE_PROXYTYPE, defaultCollision);
  dispatcher->registerClosestPointsCreateFunc(COMPOUND_SHAPE_PROXYTYPE, COMPOUND_SHAPE_PROXYTYPE, defaultClosest);
  registered = false;
}

ConvertedCompound RasterCompoundRegistration::Impl::compound(const btCompoundShape& shape) {
  const std::vector<double> print = fingerprint(shape);
  {
    std::lock_guard<std::mutex> lock(cacheMutex);
    auto found = cache.find(&shape);
    if (found != cache.end() && found->second.fingerprint == print) return found->second;
  }
  ConvertedCompound converted = convert(shape);  // outside the lock: hulls of many children take a while
  std::lock_guard<std::mutex> lock(cacheMutex);
  cache[&shape] = converted;
  return converted;
}

void RasterCompoundRegistration::Impl::recordFallback(const std::string& why) {
  std::lock_guard<std::mutex> lock(statsMutex);
  ++stats.fallbacks;
  stats.lastError = why;
}

RasterCompoundRegistration::RasterCompoundRegistration(btCollisionDispatcher* dispatcher,
                                                       const RasterCompoundOptions& options)
    : impl_(std::make_unique<Impl>(dispatcher, options)) {}

RasterCompoundRegistration::~RasterCompoundRegistration() { impl_->restoreDefaults(); }

std::unique_ptr<RasterCompoundRegistration> registerRasterCompounds(btCollisionDispatcher* dispatcher,
                                                                    const RasterCompoundOptions& options) {
  return std::make_unique<RasterCompoundRegistration>(dispatcher, options);
}

RasterCompoundStats stats(const RasterCompoundRegistration& registration) {
  auto& impl = const_cast<RasterCompoundRegistration::Impl&>(registration.impl());
  std::lock_guard<std::mutex> lock(impl.statsMutex);
  return impl.stats;
}

}  // namespace unidist::bullet
