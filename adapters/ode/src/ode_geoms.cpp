// ODE geoms → core models (unidist/adapters/ode_geoms.h).
#include "unidist/adapters/ode_geoms.h"

#include "convex_hull.h"
#include "unidist/mesh.h"
#include "unidist/primitives.h"

#include <algorithm>
#include <map>
#include <mutex>
#include <vector>

namespace unidist {
namespace {

using Vec = Eigen::Vector3d;

Vec toVec(const dReal* v) { return Vec(v[0], v[1], v[2]); }

/// Converted trimeshes and convexes, keyed by their ODE data (trimesh) or geom (convex); `signature` holds a few
/// local vertices that tell a reused key from the one converted.
struct CachedModel {
  std::shared_ptr<const Model> model;
  std::size_t count = 0;
  std::vector<Vec> signature;
};

struct ConversionCache {
  std::mutex mutex;
  std::map<const void*, CachedModel> entries;
};

ConversionCache& cache() {
  static ConversionCache c;  // process-wide like ODE's own class tables; guarded by its mutex
  return c;
}

bool sameSignature(const CachedModel& c, std::size_t count, const std::vector<Vec>& sig, double slack) {
  if (!c.model || c.count != count || c.signature.size() != sig.size()) return false;
  for (std::size_t i = 0; i < sig.size(); ++i)
    if ((c.signature[i] - sig[i]).norm() > slack) return false;
  return true;
}

/// A triangle of the trimesh geom in its local frame (ODE hands out world vertices only). The same world value
/// always maps to the same local value, so shared vertices stay bit-identical and weld.
std::array<Vec, 3> localTriangle(dGeomID g, int index, const Eigen::Isometry3d& X_MW) {
  dVector3 a, b, c;
  dGeomTriMeshGetTriangle(g, index, &a, &b, &c);
  return {X_MW * toVec(a), X_MW * toVec(b), X_MW * toVec(c)};
}

std::shared_ptr<const Model> triMeshModel(dGeomID g) {
  const int n = dGeomTriMeshGetTriangleCount(g);
  if (n <= 0) throw InputError("ODE trimesh geom has no triangles");
  const Eigen::Isometry3d X_MW = odeGeomPose(g).inverse();
  const std::array<Vec, 3> first = localTriangle(g, 0, X_MW), last = localTriangle(g, n - 1, X_MW);
  const std::vector<Vec> sig{first[0], first[1], first[2], last[0], last[1], last[2]};
  const void* key = dGeomTriMeshGetData(g);
  ConversionCache& cc = cache();
  {
    std::lock_guard<std::mutex> lock(cc.mutex);
    auto it = cc.entries.find(key);
    if (it != cc.entries.end() &&
        sameSignature(it->second, static_cast<std::size_t>(n), sig, 1e-9 * (1 + it->second.model->localBounds().diagonal())))
      return it->second.model;
  }
  std::vector<Vec> vertices;
  std::vector<TriangleMesh::Triangle> triangles;
  vertices.reserve(3 * static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    for (const Vec& v : localTriangle(g, i, X_MW)) vertices.push_back(v);
    const auto base = static_cast<std::uint32_t>(3 * i);
    triangles.push_back({base, base + 1, base + 2});
  }
  auto model = std::make_shared<const TriangleMesh>(std::move(vertices), std::move(triangles));
  std::lock_guard<std::mutex> lock(cc.mutex);
  cc.entries[key] = CachedModel{model, static_cast<std::size_t>(n), sig};
  return model;
}

/// Contacts of the convex geom against one probe plane (ODE reports one contact per vertex below the plane).
std::vector<dContactGeom> probeBelow(dGeomID convex, dGeomID plane) {
  std::vector<dContactGeom> found(1024);
  int n = dCollide(convex, plane, static_cast<int>(found.size()), found.data(), sizeof(dContactGeom));
  if (n == static_cast<int>(found.size())) {
    found.resize(0xffff);
    n = dCollide(convex, plane, static_cast<int>(found.size()), found.data(), sizeof(dContactGeom));
  }
  found.resize(static_cast<std::size_t>(std::max(n, 0)));
  return found;
}

/// The convex geom's vertices in its local frame, read through ODE's convex–plane collider (the only public
/// access to them): it reports every vertex below a plane, but only when the plane cuts the geom. Two planes at a
/// quarter and three quarters of the height, facing opposite ways, cover every vertex between them; a vertex seen
/// twice comes back bit-identical (the same transform of the same numbers) and is kept once.
std::vector<Vec> convexVertices(dGeomID g) {
  dReal box[6];
  dGeomGetAABB(g, box);
  const double low = box[4] + 0.25 * (box[5] - box[4]), high = box[5] - 0.25 * (box[5] - box[4]);
  dGeomID probe = dCreatePlane(nullptr, 0, 0, 1, high);
  std::vector<dContactGeom> found = probeBelow(g, probe);
  dGeomPlaneSetParams(probe, 0, 0, -1, -low);
  const std::vector<dContactGeom> above = probeBelow(g, probe);
  dGeomDestroy(probe);
  found.insert(found.end(), above.begin(), above.end());
  const Eigen::Isometry3d X_MW = odeGeomPose(g).inverse();
  std::vector<Vec> points;
  for (const dContactGeom& c : found) {
    const Vec p = X_MW * toVec(c.pos);
    if (std::find(points.begin(), points.end(), p) == points.end()) points.push_back(p);
  }
  return points;
}

std::shared_ptr<const Model> convexModel(dGeomID g) {
  const std::vector<Vec> points = convexVertices(g);
  if (points.size() < 4) throw InputError("ODE convex geom has fewer than 4 vertices");
  ConversionCache& cc = cache();
  {
    std::lock_guard<std::mutex> lock(cc.mutex);
    auto it = cc.entries.find(g);
    if (it != cc.entries.end() &&
        sameSignature(it->second, points.size(), points, 1e-9 * (1 + it->second.model->localBounds().diagonal())))
      return it->second.model;
  }
  auto model = std::make_shared<const TriangleMesh>(points, odeadapt::convexHull(points));
  std::lock_guard<std::mutex> lock(cc.mutex);
  cc.entries[g] = CachedModel{model, points.size(), points};
  return model;
}

std::shared_ptr<const Model> capsuleModel(dGeomID g) {
  dReal r = 0, length = 0;
  dGeomCapsuleGetParams(g, &r, &length);
  if (length == 0) return std::make_shared<const Sphere>(r);  // ODE allows a zero-length capsule
  return std::make_shared<const Capsule>(r, 0.5 * length);
}

std::shared_ptr<const Model> cylinderModel(dGeomID g) {
  dReal r = 0, length = 0;
  dGeomCylinderGetParams(g, &r, &length);
  return std::make_shared<const Cylinder>(r, 0.5 * length);
}

std::shared_ptr<const Model> planeModel(dGeomID g) {
  dVector4 p;
  dGeomPlaneGetParams(g, p);
  return std::make_shared<const Plane>(Vec(p[0], p[1], p[2]), p[3]);
}

}  // namespace

std::string odeClassName(int c) {
  switch (c) {
    case dSphereClass: return "sphere";
    case dBoxClass: return "box";
    case dCapsuleClass: return "capsule";
    case dCylinderClass: return "cylinder";
    case dPlaneClass: return "plane";
    case dRayClass: return "ray";
    case dConvexClass: return "convex";
    case dGeomTransformClass: return "geom transform";
    case dTriMeshClass: return "trimesh";
    case dHeightfieldClass: return "heightfield";
    default: break;
  }
  if (c >= dFirstSpaceClass && c <= dLastSpaceClass) return "space";
  return "user class " + std::to_string(c);
}

bool odeClassHasModel(int c) {
  switch (c) {
    case dSphereClass: case dBoxClass: case dCapsuleClass: case dCylinderClass: case dPlaneClass:
    case dConvexClass: case dTriMeshClass:
      return true;
    default:
      return false;
  }
}

std::shared_ptr<const Model> modelFromOdeGeom(dGeomID g) {
  if (!g) throw InputError("modelFromOdeGeom: null geom");
  const int c = dGeomGetClass(g);
  switch (c) {
    case dSphereClass: return std::make_shared<const Sphere>(dGeomSphereGetRadius(g));
    case dBoxClass: {
      dVector3 lengths;
      dGeomBoxGetLengths(g, lengths);
      return std::make_shared<const Box>(0.5 * toVec(lengths));
    }
    case dCapsuleClass: return capsuleModel(g);
    case dCylinderClass: return cylinderModel(g);
    case dPlaneClass: return planeModel(g);
    case dConvexClass: return convexModel(g);
    case dTriMeshClass: return triMeshModel(g);
    case dHeightfieldClass:
      throw InputError("ODE heightfield geoms have no model here (ODE 0.16 gives no public access to the samples): "
                       "register the data with unidist::ode::describeHeightfield");
    default:
      throw InputError("ODE geom class '" + odeClassName(c) + "' has no unidist model");
  }
}

Eigen::Isometry3d odeGeomPose(dGeomID g) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  if (!dGeomIsSpace(g) && dGeomGetClass(g) == dPlaneClass) return X;  // not placeable: model in world coordinates
  if (!dGeomIsSpace(g) && dGeomGetClass(g) == dHeightfieldClass) {
    // Heightfields may be created non-placeable (frame = world), and dGeomGetPosition must not be called on
    // those; ODE's local-to-world helpers work for both kinds.
    dVector3 o, axis;
    dGeomGetRelPointPos(g, 0, 0, 0, o);
    X.translation() = toVec(o);
    for (int j = 0; j < 3; ++j) {
      dGeomVectorToWorld(g, j == 0, j == 1, j == 2, axis);
      X.linear().col(j) = toVec(axis);
    }
    return X;
  }
  const dReal* p = dGeomGetPosition(g);
  const dReal* R = dGeomGetRotation(g);  // row-major 3x4
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) X.linear()(i, j) = R[4 * i + j];
  X.translation() = toVec(p);
  return X;
}

void forgetOdeTriMeshData(dTriMeshDataID data) {
  std::lock_guard<std::mutex> lock(cache().mutex);
  cache().entries.erase(data);
}

void forgetOdeCache() {
  std::lock_guard<std::mutex> lock(cache().mutex);
  cache().entries.clear();
}

}  // namespace unidist
