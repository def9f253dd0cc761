// FCL 0.7 on the dial's cases. Its dials: distance_tolerance (where GJK stops) and abs_err (how much nearer a
// bounding-volume pair must promise to be before it is opened), both set to the tolerance we are asked for.
// Primitive pairs: signed distance through libccd (GJK + EPA), and FCL's own GJK on the apart cases (its EPA
// aborts on penetration, docs/accuracy.md). Meshes: BVHModel<OBBRSS>, which measures no penetration depth, so
// apart cases only; NURBS against a mesh: the NURBS tessellated ever finer (dial_tessellate.h).
#include "bench/dial_peers.h"
#include "bench/dial_tessellate.h"
#include "bench/mesh_vs_fcl_util.h"

#include <fcl/fcl.h>

#include <map>
#include <memory>

namespace dial {
namespace {

using bench::fclPose;
using FclGeometry = std::shared_ptr<fcl::CollisionGeometryd>;

FclGeometry fclMesh(const Soup& s) {
  auto g = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  std::vector<fcl::Triangle> t;
  for (const Tri& tri : s.triangles) t.emplace_back(tri[0], tri[1], tri[2]);
  g->beginModel();
  g->addSubModel(s.vertices, t);
  g->endModel();
  return g;
}

FclGeometry fclGeometry(const Geometry& g) {
  if (g.kind == Geometry::Kind::Mesh) return fclMesh(g.soup);
  if (g.kind != Geometry::Kind::Primitive) return nullptr;
  const oracle::Shape& s = g.shape;
  if (s.kind == "box") return std::make_shared<fcl::Boxd>(2 * s.p0, 2 * s.p1, 2 * s.p2);
  if (s.kind == "capsule") return std::make_shared<fcl::Capsuled>(s.p0, 2 * s.p1);
  if (s.kind == "cylinder") return std::make_shared<fcl::Cylinderd>(s.p0, 2 * s.p1);
  if (s.kind == "cone") return std::make_shared<fcl::Coned>(s.p0, 2 * s.p1);
  if (s.kind == "sphere") return std::make_shared<fcl::Sphered>(s.p0);
  return nullptr;  // FCL has no torus
}

struct Query {
  FclGeometry a, b;  // a mesh (when there is one) first: FCL's table has mesh–shape, not shape–mesh
  fcl::Transform3d Ta, Tb;
  fcl::DistanceRequestd request;
  double operator()() const {
    fcl::DistanceResultd result;
    fcl::distance(a.get(), Ta, b.get(), Tb, request, result);
    return result.min_distance;
  }
};

/// FCL's answer on a case, or nothing when one side has no FCL form or a mesh would need a penetration depth.
Prepared prepare(const Case& c, const FclGeometry& ga, const FclGeometry& gb, double relative,
                 fcl::GJKSolverType solver, bool apartOnly) {
  if (!ga || !gb || (apartOnly && c.penetrating)) return {};
  const bool swap = c.b->kind == Geometry::Kind::Mesh && c.a->kind != Geometry::Kind::Mesh;
  const double tol = relative * c.size;
  Query q{swap ? gb : ga, swap ? ga : gb, fclPose(swap ? c.Xb : c.Xa), fclPose(swap ? c.Xa : c.Xb),
          fcl::DistanceRequestd(true, !apartOnly, 0.0, tol, tol, solver)};
  return {q, relative};
}

}  // namespace

void fclPeers(const Family& f) {
  std::map<const Geometry*, FclGeometry> cache;
  auto geometry = [&](const GeometryPtr& g) {
    auto it = cache.find(g.get());
    return it != cache.end() ? it->second : (cache[g.get()] = fclGeometry(*g));
  };
  const std::vector<double> tolerances = decades();
  const int n = static_cast<int>(tolerances.size());
  if (f.name == "prim-prim") {
    peerRows(f, "FCL libccd", n, [&](const Case& c, int k) {
      return prepare(c, geometry(c.a), geometry(c.b), tolerances[static_cast<std::size_t>(k)], fcl::GST_LIBCCD, false);
    }, true);
    peerRows(f, "FCL own GJK (apart only)", n, [&](const Case& c, int k) {
      return prepare(c, geometry(c.a), geometry(c.b), tolerances[static_cast<std::size_t>(k)], fcl::GST_INDEP, true);
    }, true);
  }
  if (f.name == "prim-mesh" || f.name == "mesh-mesh") {
    peerRows(f, "FCL OBBRSS (apart only)", n, [&](const Case& c, int k) {
      return prepare(c, geometry(c.a), geometry(c.b), tolerances[static_cast<std::size_t>(k)], fcl::GST_LIBCCD, true);
    }, true);
  }
  if (f.name == "mesh-nurbs") {  // the NURBS side (B) tessellated at each resolution, FCL at its default settings
    const std::vector<int> steps = tessellationSteps();
    std::map<std::pair<const Geometry*, int>, std::pair<FclGeometry, double>> tessellated;  // → mesh, deflection
    peerRows(f, "FCL OBBRSS on tessellated NURBS (apart only)", static_cast<int>(steps.size()), [&](const Case& c, int k) -> Prepared {
      if (c.penetrating || c.b->kind != Geometry::Kind::Nurbs) return {};
      const int step = steps[static_cast<std::size_t>(k)];
      auto& t = tessellated[{c.b.get(), step}];
      if (!t.first) {
        const Tessellation mesh = tessellate(c.b->surfaces.front(), step);
        t = {fclMesh(mesh.soup), mesh.deflection};
      }
      return {Query{geometry(c.a), t.first, fclPose(c.Xa), fclPose(c.Xb), fcl::DistanceRequestd(true)}, t.second / c.size};
    }, true);
  }
}

}  // namespace dial
