// unidist models as ODE geoms: one user geom class whose collider serves every ODE class, so that an ordinary
// ODE loop (dSpaceCollide → nearCallback → dCollide → dJointCreateContact) works with NURBS, meshes, point
// clouds and primitives against sphere, box, capsule, cylinder, plane, ray, convex, trimesh and other unidist
// geoms. See docs/ode.md.
//
// Registration: call init() after dInitODE2(0) and before creating unidist geoms. init() is idempotent; after
// dCloseODE() + dInitODE2() ODE has forgotten every user class, and init() notices it (it keeps a marker in ODE's
// collider table: the ray–ray cell, which ODE leaves empty, and checks whether the marker is still there) and
// registers again. ODE allows 4 user classes per process; unidist uses one.
//
// Contacts (dCollide / a nearCallback): unidist::manifoldContacts of the unidist model against the other geom
// turned into a core model (adapters/ode: unidist/adapters/ode_geoms.h), honouring the caller's maximum
// (flags & 0xffff) and stride (skip); when more regions touch than fit, the deepest and most spread are kept.
// Conventions are ODE's: pos in the world (midway between the two surface points), normal unit and pointing
// from g2 into g1 (moving g1 by depth along it separates the pair), depth >= 0 (only touching or penetrating
// points are emitted), side1/side2 = the models' feature ids (for an ODE trimesh: the triangle index ODE uses;
// -1 for ODE primitives). ODE swaps g1/g2 and negates normals itself when the unidist geom is the second argument.
//
// Rays (dRayClass): the first hit of the ray with the model's surface (unidist/raycast.h), one contact with
// depth = distance along the ray and the normal facing the ray (ODE's convention for its own ray colliders,
// seen from the ray as g1). A ray starting inside a solid reports where it leaves, as ODE's sphere and box do;
// with dGeomRaySetBackfaceCull it reports the next entry instead (or nothing).
//
// Heightfields (dHeightfieldClass): ODE 0.16 gives no access to their samples; describe the data once with
// unidist::ode::describeHeightfield (unidist/ode/heightfield.h) and its geoms collide like any other class. Pairs
// with a heightfield whose data was not described produce no contacts. A geom transform (dGeomTransformClass)
// holding a unidist geom goes through ODE's own transform code (not tested yet); prefer
// dGeomSetOffsetPosition/Rotation.
//
// Warm start: each (unidist geom, other geom) pair keeps a unidist::ContactCache between steps (a resting pair
// is updated locally instead of searched again). The entry is dropped when the unidist geom is destroyed, and
// reset when the other geom's class or bounds change (an ODE geom destroyed and its address reused).
//
// Tolerance: the absolute accuracy of a pair's queries is the smaller of the two geoms' setTolerance values; by
// default 1e-4 × the smaller bounding-box diagonal of the pair (unidist::ManifoldOptions). setQueryOptions sets
// the whole dial (relative tolerance, iteration cap); a pair uses the stricter of the two.
//
// AABB: the model's local bounds moved by the geom's current pose (a half-space model: infinite). The model
// is immutable, so dGeomMoved is only needed when the pose is changed by other means than ODE's own setters.
//
// Threads: like ODE's collision, call from one thread at a time per world; the plugin's shared state (class id,
// pair caches) is guarded by a mutex. Errors inside a collider cannot be thrown through ODE: they are reported
// with dMessage, the pair gets no contacts, and lastError() returns the message.
#pragma once

#include "unidist/model.h"
#include "unidist/query_options.h"

#include <ode/ode.h>

#include <memory>
#include <string>

namespace unidist::ode {

/// Registers the geom class (after dInitODE2; idempotent; registers again after dCloseODE + dInitODE2).
void init();

/// The registered ODE class id, or -1 before init().
int geomClass();

/// A placeable geom of the unidist class holding `model` (its local frame = the model frame), added to `space`
/// when it is not null. Throws InputError for a null model, or std::logic_error when init() was not called.
dGeomID createGeom(dSpaceID space, std::shared_ptr<const Model> model);

/// The model of a unidist geom; null for geoms of other classes.
std::shared_ptr<const Model> geomModel(dGeomID g);

/// Absolute query accuracy for this geom's contacts (> 0); a negative value restores the default.
/// Throws InputError for a geom that is not a unidist geom, or a zero / non-finite tolerance.
void setTolerance(dGeomID g, double tolerance);
/// The value set by setTolerance, or -1 (the default).
double tolerance(dGeomID g);

/// The whole dial of this geom's queries (unidist/query_options.h); a pair uses the stricter of its two geoms'
/// dials, each geom its own level of detail (detailA: its model's stand-in, Model::atDetail, answers its
/// contacts; detailB is ignored). The tolerance follows setTolerance's rules. Throws InputError for a geom that is not a unidist geom or
/// an invalid setting.
void setQueryOptions(dGeomID g, const QueryOptions& options);
QueryOptions queryOptions(dGeomID g);

/// The last error a collider reported (empty when none).
std::string lastError();

/// Number of warm-start caches currently held (for tests and benchmarks).
std::size_t pairCacheCount();

}  // namespace unidist::ode
