// The one collider of the unidist geom class: o1 is always the unidist geom (ODE swaps the arguments and negates
// the normals itself when the caller passed it second), o2 any supported class.
#include "plugin_state.h"
#include "unidist/adapters/ode_geoms.h"
#include "unidist/mesh.h"
#include "unidist/raycast.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <tuple>

namespace unidist::ode::detail {
namespace {

/// A body's velocities are finite (true for a geom without a body).
bool finiteVelocity(dGeomID g) {
  const dBodyID b = dGeomGetBody(g);
  if (!b) return true;
  const dReal* v = dBodyGetLinearVel(b);
  const dReal* w = dBodyGetAngularVel(b);
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(v[i]) || !std::isfinite(w[i])) return false;
  return true;
}

dContactGeom* slot(dContactGeom* contacts, int i, int skip) {
  return reinterpret_cast<dContactGeom*>(reinterpret_cast<char*>(contacts) + static_cast<std::ptrdiff_t>(i) * skip);
}

void put(dReal* out, const Eigen::Vector3d& v) {
  out[0] = v.x();
  out[1] = v.y();
  out[2] = v.z();
}

/// The dial of a pair: the stricter of the two geoms' (a negative tolerance: ManifoldOptions' default).
QueryOptions pairDial(const GeomRecord& a, const GeomRecord* b) { return dialOfPair(a.query, b ? &b->query : nullptr); }

/// Default ray accuracy: 1e-4 × the model's bounding diagonal (1e-9 for an unbounded model).
double rayTolerance(const GeomRecord& a) {
  if (a.query.tolerance > 0) return a.query.tolerance;
  const Aabb box = a.model->localBounds();
  return box.bounded() && box.diagonal() > 0 ? 1e-4 * box.diagonal() : 1e-9;
}

int rayContact(dGeomID o1, const GeomRecord& a, dGeomID ray, dContactGeom* out) {
  dVector3 start, dir;
  dGeomRayGet(ray, start, dir);
  const Eigen::Vector3d origin(start[0], start[1], start[2]);
  const Eigen::Vector3d d = Eigen::Vector3d(dir[0], dir[1], dir[2]).normalized();
  const double length = dGeomRayGetLength(ray);
  const double tol = rayTolerance(a);
  const Eigen::Isometry3d X_WA = odeGeomPose(o1);
  RayHit hit = raycast(*a.model, X_WA, origin, d, length, tol);
  if (hit.hit && hit.startedInside && dGeomRayGetBackfaceCull(ray)) {
    // Culled back face: look for the next entry past the exit point.
    const double skipTo = hit.t + 4 * tol;
    if (skipTo >= length) return 0;
    hit = raycast(*a.model, X_WA, origin + skipTo * d, d, length - skipTo, tol);
    if (!hit.hit || hit.startedInside) return 0;
    hit.t += skipTo;
  }
  if (!hit.hit) return 0;
  put(out->pos, hit.point);
  put(out->normal, -hit.normal);  // seen from g1 = the unidist geom; ODE negates it for dCollide(ray, geom)
  out->depth = hit.t;
  out->g1 = o1;
  out->g2 = ray;
  out->side1 = hit.feature;
  out->side2 = -1;
  return 1;
}

/// ODE's feature id on the other geom: the trimesh's own triangle index, nothing for ODE's primitives.
int otherSide(int otherClass, const Model& b, int featureB, bool otherIsUnidist) {
  if (otherIsUnidist) return featureB;
  if (otherClass == dTriMeshClass || otherClass == dHeightfieldClass)  // heightfield: our mesh's triangle index
    return static_cast<int>(static_cast<const TriangleMesh&>(b).sourceTriangle(featureB));
  return -1;
}

int modelContacts(dGeomID o1, const GeomRecord& a, dGeomID o2, int maxc, dContactGeom* contacts, int skip) {
  const int otherClass = dGeomGetClass(o2);
  const GeomRecord* b = record(o2);
  std::shared_ptr<const Model> modelB;
  std::uint64_t version = 0;
  if (b) {
    modelB = b->model;
  } else if (otherClass == dHeightfieldClass) {
    std::tie(modelB, version) = describedHeightfield(dGeomHeightfieldGetHeightfieldData(o2));
    if (!modelB) return 0;  // data never described: no contacts, as without the plugin (heightfield.h)
  } else {
    modelB = modelFromOdeGeom(o2);
  }
  const Eigen::Isometry3d X_WA = odeGeomPose(o1), X_WB = odeGeomPose(o2);

  ManifoldOptions options;
  static_cast<QueryOptions&>(options) = pairDial(a, b);
  options.maxContacts = maxc;
  ContactCache& cache = pairCache(o1, o2, otherClass, modelB->localBounds(), version);
  const std::vector<Contact> found = manifoldContacts(*a.model, X_WA, *modelB, X_WB, options, &cache);

  int n = 0;
  for (const Contact& c : found) {
    if (c.distance > 0) continue;  // ODE wants touching or penetrating points only
    dContactGeom* g = slot(contacts, n, skip);
    put(g->pos, 0.5 * (c.pointA + c.pointB));
    put(g->normal, -c.normal);  // unidist: A toward B; ODE: from g2 into g1
    g->depth = -c.distance;
    g->g1 = o1;
    g->g2 = o2;
    g->side1 = c.featureA;
    g->side2 = otherSide(otherClass, *modelB, c.featureB, b != nullptr);
    if (++n == maxc) break;
  }
  return n;
}

}  // namespace

int collide(dGeomID o1, dGeomID o2, int flags, dContactGeom* contacts, int skip) {
  const int maxc = flags & 0xffff;
  if (maxc < 1) return 0;
  try {
    const GeomRecord* a = record(o1);
    if (!a || !a->model) return 0;  // not ours (cannot happen through ODE's table) or already destroyed
    if (!finiteVelocity(o1) || !finiteVelocity(o2)) {  // a contact would hand ODE's solver the NaN: skip the pair
      reportError("collider: non-finite body velocity; pair skipped");
      return 0;
    }
    if (dGeomGetClass(o2) == dRayClass) return rayContact(o1, *a, o2, contacts);
    if (const GeomRecord* b = record(o2); a->pieces && b && b->pieces)
      return convexUnionContacts(o1, *a, o2, *b, maxc, contacts);
    return modelContacts(o1, *a, o2, maxc, contacts, skip);
  } catch (const std::exception& e) {
    reportError(std::string("collider: ") + e.what());
  } catch (...) {
    reportError("collider: unknown exception");
  }
  return 0;
}

}  // namespace unidist::ode::detail
