// Shared state of the ODE plugin: the registered class, the per-geom records and the per-pair warm-start caches.
#pragma once

#include "unidist/contact_manifold.h"
#include "unidist/model.h"
#include "unidist/query_options.h"

#include <ode/ode.h>

#include <cstdint>
#include <memory>
#include <string>
#include <utility>

namespace unidist::ode::detail {

/// A convex decomposition attached to a geom (unidist/ode/convex_union.h; defined in convex_union.cpp).
struct ConvexPieces;

/// What a unidist geom owns (ODE's class data holds only a pointer to it: raw zeroed memory, no constructors).
struct GeomRecord {
  std::shared_ptr<const Model> model;
  QueryOptions query;  ///< the geom's dial (setQueryOptions / setTolerance); tolerance -1: the default
  std::shared_ptr<const ConvexPieces> pieces;  ///< set for convex-union geoms only
};

/// Contacts of two convex-union geoms by the image-space penetration depth (convex_union.cpp; 0 contacts when
/// the raster target was not built, which never happens: such geoms cannot be created then).
int convexUnionContacts(dGeomID o1, const GeomRecord& a, dGeomID o2, const GeomRecord& b, int maxc,
                        dContactGeom* contacts);

/// The record of a unidist geom, or null for other geoms.
GeomRecord* record(dGeomID g);

/// The warm-start cache of the pair (unidist geom a, other geom b), reset when b's class or bounds differ from
/// the ones it was filled with, or when `otherVersion` differs (a heightfield's registration serial, new on every
/// describeHeightfield; 0 for classes whose model is rebuilt per query). The reference stays valid until the
/// pair's entry is erased (a geom destroyed).
ContactCache& pairCache(dGeomID a, dGeomID b, int otherClass, const Aabb& otherBounds, std::uint64_t otherVersion = 0);

/// The described model of a heightfield data and its registration serial (> 0; unique per describeHeightfield
/// call in the process), or {null, 0} (heightfield.cpp).
std::pair<std::shared_ptr<const Model>, std::uint64_t> describedHeightfield(dHeightfieldDataID data);

/// Remembers a collider's error for lastError() and prints it through dMessage.
void reportError(const std::string& message);

/// The one collider of the class (collider.cpp): o1 is the unidist geom, o2 any supported geom.
int collide(dGeomID o1, dGeomID o2, int flags, dContactGeom* contacts, int skip);

}  // namespace unidist::ode::detail
