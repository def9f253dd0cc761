// The registration object: the create functions and the cache of converted Bullet shapes. Internal.
#pragma once

#include "unidist/adapters/bullet_shapes.h"
#include "unidist/bullet/plugin.h"

#include <atomic>
#include <mutex>
#include <string>
#include <unordered_map>
#include <vector>

namespace unidist::bullet {

/// Converted Bullet shapes, shared by all pairs: a static triangle mesh is converted (and gets its hierarchy)
/// once, not once per body touching it. Entries are checked against a fingerprint of the shape (type, AABB,
/// margin, scaling), so a shape deleted and another created at the same address is converted again.
class ShapeModelCache {
 public:
  ConvertedShape get(const btCollisionShape& shape);

 private:
  struct Entry {
    std::vector<double> fingerprint;
    ConvertedShape converted;
  };
  std::mutex mutex_;
  std::unordered_map<const btCollisionShape*, Entry> entries_;
};

struct Registration::Impl {
  explicit Impl(btCollisionDispatcher* dispatcher);
  void restoreDefaults();

  btCollisionDispatcher* dispatcher;
  std::vector<std::pair<int, int>> cells;  // every (type0, type1) written
  std::unique_ptr<btCollisionAlgorithmCreateFunc> forward, reverse;
  ShapeModelCache shapeCache;
  std::atomic<long> globalSearches{0}, localUpdates{0};
  /// A pair skipped for one step (see PluginStats).
  void noteSkip(const std::string& why);
  std::atomic<long> skippedPairs{0};
  mutable std::mutex errorMutex;
  std::string lastError;  // guarded by errorMutex
};

}  // namespace unidist::bullet
