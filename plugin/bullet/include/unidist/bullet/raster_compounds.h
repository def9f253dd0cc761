// Opt-in: the image-space penetration depth of unidist::raster (docs/raster.md) for pairs of Bullet compounds whose
// children are convex hulls or boxes (a convex decomposition). Bullet's own compound–compound algorithm answers
// each child pair alone, so two interpenetrating non-convex bodies get a per-child depth and direction; this one
// answers the pair as a whole: one contact per step at the minimum translation that separates the two unions
// (the persistent manifold keeps up to four over steps, as for Bullet's convex pairs), certified separation
// distances otherwise. Available when unidist was built with the raster target (libosmesa6-dev, libqhull-dev).
//
//   auto unidistPlugin = unidist::bullet::registerAlgorithms(&dispatcher);
//   auto rasterPairs = unidist::bullet::registerRasterCompounds(&dispatcher, {/*resolution*/ 128});
//   // teardown: the world, then rasterPairs, then unidistPlugin, then the dispatcher
//
// Compounds with another child type (or degenerate hulls) keep the configuration's own algorithm; stats() counts
// them. Conversions are cached per compound shape (a shape changed in place at the same address with the same
// bounds is not noticed: make a new shape). One off-screen context per registration, created on the first
// query, serialises the image-space queries of a multithreaded dispatcher.
#pragma once

#include <btBulletCollisionCommon.h>

#include <memory>
#include <string>

namespace unidist::bullet {

struct RasterCompoundOptions {
  int resolution = 128;   ///< pixels per side of each cube face (8..4096): the accuracy of the depth
  double tolerance = -1;  ///< separation accuracy; negative: 1e-4 × the smaller compound's bounding-box diagonal
};

class RasterCompoundRegistration {
 public:
  RasterCompoundRegistration(btCollisionDispatcher* dispatcher, const RasterCompoundOptions& options);
  ~RasterCompoundRegistration();  ///< puts the configuration's compound–compound algorithm back
  RasterCompoundRegistration(const RasterCompoundRegistration&) = delete;
  RasterCompoundRegistration& operator=(const RasterCompoundRegistration&) = delete;

  struct Impl;  // internal
  Impl& impl() { return *impl_; }
  const Impl& impl() const { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

/// Installs the algorithm in the compound–compound cell of both tables. Throws InputError for a null dispatcher
/// or a resolution outside 8..4096.
std::unique_ptr<RasterCompoundRegistration> registerRasterCompounds(btCollisionDispatcher* dispatcher,
                                                                    const RasterCompoundOptions& options = {});

struct RasterCompoundStats {
  long queries = 0;      ///< image-space pair queries run
  long penetrating = 0;  ///< of which found the unions overlapping
  long fallbacks = 0;    ///< pairs handed to Bullet's own algorithm (a child that is not convex)
  std::string lastError; ///< why the last fallback or failed query happened
};
RasterCompoundStats stats(const RasterCompoundRegistration& registration);

}  // namespace unidist::bullet
