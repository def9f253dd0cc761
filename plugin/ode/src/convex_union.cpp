// Convex-union geoms (unidist/ode/convex_union.h): the pieces' hulls, the hull triangles as the geom's mesh, and
// the one-contact collider of two such geoms through unidist::raster::unionDistance.
#include "plugin_state.h"
#include "unidist/adapters/ode_geoms.h"
#include "unidist/mesh.h"
#include "unidist/ode/convex_union.h"
#include "unidist/ode/geom.h"

#ifdef UNIDIST_HAVE_RASTER
#include "unidist/raster/convex_piece.h"

#include <mutex>
#endif

namespace unidist::ode {

#ifdef UNIDIST_HAVE_RASTER
namespace detail {

struct ConvexPieces {
  raster::ConvexUnion pieces;
  int resolution = 128;
  double diagonal = 0;
};

namespace {

/// The plugin's one off-screen context, made on the first image-space query (ODE collides from one thread per
/// world; the mutex covers several worlds on several threads).
struct RasterState {
  std::mutex mutex;
  std::unique_ptr<raster::OffscreenContext> context;
};

RasterState& rasterState() {
  static RasterState s;
  return s;
}

void put(dReal* out, const Eigen::Vector3d& v) {
  out[0] = v.x();
  out[1] = v.y();
  out[2] = v.z();
}

}  // namespace

int convexUnionContacts(dGeomID o1, const GeomRecord& a, dGeomID o2, const GeomRecord& b, int maxc,
                        dContactGeom* contacts) {
  if (maxc < 1) return 0;
  raster::UnionDistanceOptions options;
  options.resolution = std::max(a.pieces->resolution, b.pieces->resolution);
  const double tolerance = stricter(a.query, b.query).tolerance;
  options.tolerance = tolerance > 0 ? tolerance : 1e-4 * std::min(a.pieces->diagonal, b.pieces->diagonal);
  DistanceResult r;
  {
    RasterState& s = rasterState();
    std::lock_guard<std::mutex> lock(s.mutex);
    if (!s.context) s.context = std::make_unique<raster::OffscreenContext>(options.resolution, options.resolution);
    r = raster::unionDistance(*s.context, a.pieces->pieces, odeGeomPose(o1), b.pieces->pieces, odeGeomPose(o2),
                              options);
  }
  if (r.distance > 0) return 0;  // ODE wants touching or penetrating points only
  put(contacts->pos, 0.5 * (r.pointA + r.pointB));
  put(contacts->normal, -r.normal);  // unidist: the way B moves to separate; ODE: from g2 into g1
  contacts->depth = -r.distance;
  contacts->g1 = o1;
  contacts->g2 = o2;
  contacts->side1 = -1;
  contacts->side2 = -1;
  return 1;
}

}  // namespace detail

dGeomID createConvexUnionGeom(dSpaceID space, const std::vector<std::vector<Eigen::Vector3d>>& pieces,
                              int resolution) {
  if (pieces.empty()) throw InputError("unidist::ode::createConvexUnionGeom: no pieces");
  if (resolution < 8 || resolution > 4096)
    throw InputError("unidist::ode::createConvexUnionGeom: resolution must be 8..4096 (got " +
                     std::to_string(resolution) + ")");
  auto data = std::make_shared<detail::ConvexPieces>();
  data->resolution = resolution;
  std::vector<Eigen::Vector3d> vertices;
  std::vector<TriangleMesh::Triangle> triangles;
  Aabb box;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    data->pieces.push_back(raster::convexPiece(pieces[i], {}, "piece " + std::to_string(i)));
    const raster::ConvexPolytope& hull = data->pieces.back();
    const auto offset = static_cast<std::uint32_t>(vertices.size());
    for (const Eigen::Vector3d& v : hull.vertices) {
      vertices.push_back(v);
      box.extend(v);
    }
    for (const std::array<int, 3>& t : hull.triangles)
      triangles.push_back({offset + std::uint32_t(t[0]), offset + std::uint32_t(t[1]), offset + std::uint32_t(t[2])});
  }
  data->diagonal = box.diagonal();
  dGeomID g = createGeom(space, std::make_shared<TriangleMesh>(std::move(vertices), std::move(triangles)));
  detail::record(g)->pieces = std::move(data);
  return g;
}

#else  // built without the raster target: such geoms cannot exist

namespace detail {
int convexUnionContacts(dGeomID, const GeomRecord&, dGeomID, const GeomRecord&, int, dContactGeom*) { return 0; }
}  // namespace detail

dGeomID createConvexUnionGeom(dSpaceID, const std::vector<std::vector<Eigen::Vector3d>>&, int) {
  throw InputError("unidist::ode::createConvexUnionGeom: unidist was built without the raster target (install "
                   "libosmesa6-dev and libqhull-dev, then rebuild)");
}

#endif

}  // namespace unidist::ode
