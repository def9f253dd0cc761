// ODE's own geom classes as core models, for the ODE plugin's collider (one collider serves every ODE class by
// turning the other geom into a unidist model). Each model lives in the geom's local frame; odeGeomPose gives
// that frame in the world (position and rotation including any body offset).
//
//   ODE class      → core model
//   dSphereClass   → Sphere(radius)
//   dBoxClass      → Box(lengths / 2)
//   dCapsuleClass  → Capsule(radius, length / 2)   (both have their axis along local z; length 0 → Sphere)
//   dCylinderClass → Cylinder(radius, length / 2)  (axis z)
//   dPlaneClass    → Plane(n, d): the solid half-space n·x <= d in WORLD coordinates (ODE planes are not
//                    placeable; odeGeomPose returns the identity for them)
//   dConvexClass   → closed convex TriangleMesh: the convex hull of the geom's vertices (read back through
//                    ODE's own convex–plane collider, the only public access to them)
//   dTriMeshClass  → TriangleMesh of the geom's triangles in its local frame, converted once per
//                    dTriMeshDataID (see the cache below)
// Other classes (heightfield, ray, transform, spaces, user classes) throw InputError naming the class: ODE 0.16
// has no public access to a heightfield's samples (the plugin builds heightfield models from the numbers the user
// registers with unidist::ode::describeHeightfield: unidist/adapters/ode_heightfield.h). odeGeomPose works for
// placeable and non-placeable heightfields (the latter: identity).
//
// Cache: converted trimeshes are kept per dTriMeshDataID and re-converted when the triangle count or the first or
// last triangle changed (a destroyed data id reused by ODE for other data is detected this way). Data edited in
// place (dGeomTriMeshDataUpdate after changing vertices) must be announced with forgetOdeTriMeshData. Convex
// geoms are kept per geom with the same kind of check. The cache is guarded by a mutex.
#pragma once

#include "unidist/model.h"

#include <ode/ode.h>

#include <memory>
#include <string>

namespace unidist {

/// The geom's shape as a core model in the geom's local frame. Throws InputError for classes without a model.
std::shared_ptr<const Model> modelFromOdeGeom(dGeomID g);

/// World pose of the geom's local frame (identity for non-placeable geoms such as planes).
Eigen::Isometry3d odeGeomPose(dGeomID g);

/// ODE's name of a geom class ("sphere", "box", ..., "user class 14"), for messages.
std::string odeClassName(int geomClass);

/// Whether modelFromOdeGeom can convert geoms of this class.
bool odeClassHasModel(int geomClass);

/// Drops the cached conversions of one trimesh data (call after editing its vertices in place), or of every
/// cached geom and data (forgetOdeCache, e.g. after dCloseODE).
void forgetOdeTriMeshData(dTriMeshDataID data);
void forgetOdeCache();

}  // namespace unidist
