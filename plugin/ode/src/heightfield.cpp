// The registry of described ODE heightfield data (unidist/ode/heightfield.h).
#include "unidist/ode/heightfield.h"

#include "plugin_state.h"
#include "unidist/adapters/ode_heightfield.h"

#include <map>
#include <mutex>

namespace unidist::ode {
namespace {

struct Described {
  std::shared_ptr<const TriangleMesh> model;
  std::uint64_t serial = 0;  // tells a re-described data apart from the model a pair cache was filled with
};

struct HeightfieldRegistry {
  std::mutex mutex;
  std::map<dHeightfieldDataID, Described> models;
  std::uint64_t lastSerial = 0;
};

HeightfieldRegistry& registry() {
  static HeightfieldRegistry r;  // process-wide, like the data ids it is keyed by
  return r;
}

/// The entry of `data` (a copy, taken under the lock), or an empty one.
Described lookup(dHeightfieldDataID data) {
  HeightfieldRegistry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  const auto it = r.models.find(data);
  return it == r.models.end() ? Described{} : it->second;
}

}  // namespace

void describeHeightfield(dHeightfieldDataID data, const double* heights, double width, double depth, int widthSamples,
                         int depthSamples, double scale, double offset, double thickness, int wrap) {
  if (!data) throw InputError("unidist::ode::describeHeightfield: null dHeightfieldDataID");
  OdeHeightfieldSpec spec;
  spec.heights = heights;
  spec.width = width;
  spec.depth = depth;
  spec.widthSamples = widthSamples;
  spec.depthSamples = depthSamples;
  spec.scale = scale;
  spec.offset = offset;
  spec.thickness = thickness;
  spec.wrap = wrap != 0;
  std::shared_ptr<const TriangleMesh> model = odeHeightfieldMesh(spec);  // validates; built outside the lock
  HeightfieldRegistry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.models[data] = Described{std::move(model), ++r.lastSerial};
}

void forgetHeightfield(dHeightfieldDataID data) {
  HeightfieldRegistry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.models.erase(data);
}

std::shared_ptr<const TriangleMesh> heightfieldModel(dHeightfieldDataID data) { return lookup(data).model; }

std::size_t heightfieldCount() {
  HeightfieldRegistry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  return r.models.size();
}

namespace detail {

std::pair<std::shared_ptr<const Model>, std::uint64_t> describedHeightfield(dHeightfieldDataID data) {
  Described d = lookup(data);
  return {std::move(d.model), d.serial};
}

}  // namespace detail
}  // namespace unidist::ode
