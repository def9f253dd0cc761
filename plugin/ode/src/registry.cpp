// Class registration, geom records and pair caches of the ODE plugin (unidist/ode/geom.h).
#include "plugin_state.h"
#include "unidist/adapters/ode_geoms.h"
#include "unidist/ode/geom.h"

#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>
#include <utility>

namespace unidist::ode {
namespace {

struct PairEntry {
  ContactCache cache;
  int otherClass = -1;
  Aabb otherBounds;
  std::uint64_t otherVersion = 0;
};

/// Process-wide like ODE's own class table (the plugin is one class per process); guarded by `mutex`.
struct PluginState {
  std::mutex mutex;
  int geomClass = -1;
  std::map<std::pair<dGeomID, dGeomID>, PairEntry> pairs;
  std::string lastError;
};

PluginState& state() {
  static PluginState s;
  return s;
}

// The ray–ray cell of ODE's collider table is empty in ODE (rays never collide with rays). init() puts this
// function there; dInitODE2 after dCloseODE rebuilds the table, and a probe collision tells the two apart.
thread_local bool markerSeen = false;
int rayRayMarker(dGeomID, dGeomID, int, dContactGeom*, int) {
  markerSeen = true;
  return 0;
}

bool markerPresent() {
  dGeomID a = dCreateRay(nullptr, 1), b = dCreateRay(nullptr, 1);
  dContactGeom unused;
  markerSeen = false;
  dCollide(a, b, 1, &unused, sizeof(dContactGeom));
  dGeomDestroy(a);
  dGeomDestroy(b);
  return markerSeen;
}

void destroyRecord(dGeomID g) {
  detail::GeomRecord* r = detail::record(g);
  if (!r) return;
  {
    PluginState& s = state();
    std::lock_guard<std::mutex> lock(s.mutex);
    for (auto it = s.pairs.begin(); it != s.pairs.end();)
      it = (it->first.first == g || it->first.second == g) ? s.pairs.erase(it) : std::next(it);
  }
  delete r;
  *static_cast<detail::GeomRecord**>(dGeomGetClassData(g)) = nullptr;
}

void computeAabb(dGeomID g, dReal aabb[6]) {
  const detail::GeomRecord* r = detail::record(g);
  const Aabb local = r ? r->model->localBounds() : Aabb{};
  if (!local.bounded() || local.empty()) {  // a half-space (or nothing): everywhere
    for (int i = 0; i < 3; ++i) aabb[2 * i] = -dInfinity, aabb[2 * i + 1] = dInfinity;
    return;
  }
  const Aabb world = local.transformed(odeGeomPose(g));
  if (!world.min.allFinite() || !world.max.allFinite()) {
    // A non-finite pose (a body that blew up): NaN bounds make ODE's hash space abort ("aabbBound" check in
    // collision_space.cpp). Everywhere instead: the collider is asked about every pair and skips them.
    for (int i = 0; i < 3; ++i) aabb[2 * i] = -dInfinity, aabb[2 * i + 1] = dInfinity;
    return;
  }
  for (int i = 0; i < 3; ++i) aabb[2 * i] = world.min[i], aabb[2 * i + 1] = world.max[i];
}

dColliderFn* colliderFor(int otherClass) {
  switch (otherClass) {
    case dSphereClass: case dBoxClass: case dCapsuleClass: case dCylinderClass: case dPlaneClass:
    case dRayClass: case dConvexClass: case dTriMeshClass:
    case dHeightfieldClass:  // no contacts unless the data was described (heightfield.h)
      return &detail::collide;
    default:
      return otherClass == geomClass() ? &detail::collide : nullptr;  // other user classes
  }
}

}  // namespace

namespace detail {

GeomRecord* record(dGeomID g) {
  const int c = geomClass();
  if (!g || c < 0 || dGeomGetClass(g) != c) return nullptr;
  return *static_cast<GeomRecord**>(dGeomGetClassData(g));
}

ContactCache& pairCache(dGeomID a, dGeomID b, int otherClass, const Aabb& otherBounds, std::uint64_t otherVersion) {
  PluginState& s = state();
  std::lock_guard<std::mutex> lock(s.mutex);
  PairEntry& e = s.pairs[{a, b}];
  const bool sameBounds = e.otherBounds.min == otherBounds.min && e.otherBounds.max == otherBounds.max;
  if (e.otherClass != otherClass || !sameBounds || e.otherVersion != otherVersion) {
    e.cache.reset();
    e.otherClass = otherClass;
    e.otherBounds = otherBounds;
    e.otherVersion = otherVersion;
  }
  return e.cache;
}

void reportError(const std::string& message) {
  {
    std::lock_guard<std::mutex> lock(state().mutex);
    state().lastError = message;
  }
  dMessage(0, "unidist: %s", message.c_str());
}

}  // namespace detail

void init() {
  PluginState& s = state();
  std::lock_guard<std::mutex> lock(s.mutex);
  if (s.geomClass >= 0 && markerPresent()) return;
  // First call, or ODE was closed and initialised again: everything keyed by old geoms is stale.
  s.pairs.clear();
  forgetOdeCache();
  dGeomClass k{};
  k.bytes = sizeof(detail::GeomRecord*);
  k.collider = &colliderFor;
  k.aabb = &computeAabb;
  k.aabb_test = nullptr;
  k.dtor = &destroyRecord;
  s.geomClass = dCreateGeomClass(&k);
  dSetColliderOverride(dRayClass, dRayClass, &rayRayMarker);
}

int geomClass() {
  std::lock_guard<std::mutex> lock(state().mutex);
  return state().geomClass;
}

dGeomID createGeom(dSpaceID space, std::shared_ptr<const Model> model) {
  if (!model) throw InputError("unidist::ode::createGeom: null model");
  const int c = geomClass();
  if (c < 0) throw std::logic_error("unidist::ode::createGeom: call unidist::ode::init() after dInitODE2 first");
  dGeomID g = dCreateGeom(c);
  *static_cast<detail::GeomRecord**>(dGeomGetClassData(g)) = new detail::GeomRecord{std::move(model), {}, nullptr};
  if (space) dSpaceAdd(space, g);
  return g;
}

std::shared_ptr<const Model> geomModel(dGeomID g) {
  const detail::GeomRecord* r = detail::record(g);
  return r ? r->model : nullptr;
}

void setTolerance(dGeomID g, double tolerance) {
  detail::GeomRecord* r = detail::record(g);
  if (!r) throw InputError("unidist::ode::setTolerance: not a unidist geom");
  if (std::isnan(tolerance) || std::isinf(tolerance) || tolerance == 0)
    throw InputError("unidist::ode::setTolerance: tolerance must be finite and > 0 (or < 0 for the default)");
  r->query.tolerance = tolerance < 0 ? -1 : tolerance;
}

double tolerance(dGeomID g) { return queryOptions(g).tolerance; }

void setQueryOptions(dGeomID g, const QueryOptions& options) {
  detail::GeomRecord* r = detail::record(g);
  if (!r) throw InputError("unidist::ode::setQueryOptions: not a unidist geom");
  if (const char* why = invalidDialSetting(options))
    throw InputError(std::string("unidist::ode::setQueryOptions: ") + why);
  setTolerance(g, options.tolerance);  // its checks and its "negative: the default"
  r->query.relativeTolerance = options.relativeTolerance;
  r->query.maxIterations = options.maxIterations;
  r->query.detailA = options.detailA;  // the geom's own level of detail
  r->query.detailB = 0;
}

QueryOptions queryOptions(dGeomID g) {
  const detail::GeomRecord* r = detail::record(g);
  if (!r) throw InputError("unidist::ode: not a unidist geom");
  return r->query;
}

std::string lastError() {
  std::lock_guard<std::mutex> lock(state().mutex);
  return state().lastError;
}

std::size_t pairCacheCount() {
  std::lock_guard<std::mutex> lock(state().mutex);
  return state().pairs.size();
}

}  // namespace unidist::ode
