// Bullet (Debian's double-precision build when installed, see CMakeLists.txt) on the dial's convex NURBS cases: the NURBS sphere tessellated ever
// finer (dial_tessellate.h) as a btConvexHullShape, against Bullet's own primitives or a second hull, through
// btGjkPairDetector with the GJK-EPA depth solver (signed: penetrating cases too). Its dial is the resolution;
// the tolerance column is the tessellation's chordal deflection. Collision margins are 0 (Bullet's default
// 0.04 would round every shape); the capsule and sphere are all margin by construction, which is exact.
#include "bench/dial_peers.h"
#include "bench/dial_tessellate.h"

#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btPointCollector.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>
#include <btBulletCollisionCommon.h>

#include <cmath>
#include <map>
#include <memory>

namespace dial {
namespace {

using ShapePtr = std::shared_ptr<btConvexShape>;

btTransform bulletPose(const Pose& X) {
  const Eigen::Matrix3d R = X.linear();
  const Vec t = X.translation();
  const btMatrix3x3 basis(static_cast<btScalar>(R(0, 0)), static_cast<btScalar>(R(0, 1)), static_cast<btScalar>(R(0, 2)),
                          static_cast<btScalar>(R(1, 0)), static_cast<btScalar>(R(1, 1)), static_cast<btScalar>(R(1, 2)),
                          static_cast<btScalar>(R(2, 0)), static_cast<btScalar>(R(2, 1)), static_cast<btScalar>(R(2, 2)));
  return btTransform(basis, btVector3(static_cast<btScalar>(t.x()), static_cast<btScalar>(t.y()), static_cast<btScalar>(t.z())));
}

ShapePtr bulletPrimitive(const oracle::Shape& s) {
  const auto f = [](double v) { return static_cast<btScalar>(v); };
  ShapePtr shape;
  if (s.kind == "box") shape = std::make_shared<btBoxShape>(btVector3(f(s.p0), f(s.p1), f(s.p2)));
  if (s.kind == "cylinder") shape = std::make_shared<btCylinderShapeZ>(btVector3(f(s.p0), f(s.p0), f(s.p1)));
  if (s.kind == "cone") shape = std::make_shared<btConeShapeZ>(f(s.p0), f(2 * s.p1));
  if (s.kind == "capsule") return std::make_shared<btCapsuleShapeZ>(f(s.p0), f(2 * s.p1));
  if (s.kind == "sphere") return std::make_shared<btSphereShape>(f(s.p0));
  if (shape) shape->setMargin(0);
  return shape;
}

ShapePtr bulletHull(const Soup& s) {
  auto hull = std::make_shared<btConvexHullShape>();
  for (const Vec& v : s.vertices)
    hull->addPoint(btVector3(static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()), static_cast<btScalar>(v.z())), false);
  hull->recalcLocalAabb();
  hull->setMargin(0);
  return hull;
}

double bulletDistance(const btConvexShape* a, const btTransform& Ta, const btConvexShape* b, const btTransform& Tb) {
  btVoronoiSimplexSolver simplex;
  btGjkEpaPenetrationDepthSolver epa;
  btGjkPairDetector gjk(a, b, &simplex, &epa);
  btDiscreteCollisionDetectorInterface::ClosestPointInput input;
  input.m_transformA = Ta;
  input.m_transformB = Tb;
  btPointCollector out;
  gjk.getClosestPoints(input, out, nullptr);
  return out.m_hasResult ? static_cast<double>(out.m_distance) : std::nan("");
}

}  // namespace

void bulletPeers(const Family& f) {
  if (f.name != "prim-nurbs" && f.name != "nurbs-nurbs") return;
  const std::vector<int> steps = tessellationSteps();
  std::map<std::pair<const Geometry*, int>, std::pair<ShapePtr, double>> hulls;  // (NURBS, resolution) → hull, deflection
  std::map<const Geometry*, ShapePtr> primitives;
  // A convex model as a Bullet shape: the NURBS sphere as a hull at this resolution, a primitive as itself.
  auto shapeOf = [&](const GeometryPtr& g, int step, double& deflection) -> ShapePtr {
    if (g->kind == Geometry::Kind::Primitive) {
      auto it = primitives.find(g.get());
      return it != primitives.end() ? it->second : (primitives[g.get()] = bulletPrimitive(g->shape));
    }
    if (g->kind != Geometry::Kind::Nurbs || g->name.find("sphere") == std::string::npos) return nullptr;  // not convex
    auto& h = hulls[{g.get(), step}];
    if (!h.first) {
      const Tessellation t = tessellate(g->surfaces.front(), step);
      h = {bulletHull(t.soup), t.deflection};
    }
    deflection = std::max(deflection, h.second);
    return h.first;
  };
  const std::string bullet = sizeof(btScalar) == 8 ? "Bullet (double)" : "Bullet (float)";
  const std::string method = bullet + (f.name == "prim-nurbs" ? " GJK-EPA on tessellated NURBS" : " GJK-EPA on tessellated NURBS (sphere pairs)");
  peerRows(f, method, static_cast<int>(steps.size()), [&](const Case& c, int k) -> Prepared {
    double deflection = 0;
    const int step = steps[static_cast<std::size_t>(k)];
    const ShapePtr a = shapeOf(c.a, step, deflection), b = shapeOf(c.b, step, deflection);
    if (!a || !b) return {};
    const btTransform Ta = bulletPose(c.Xa), Tb = bulletPose(c.Xb);
    return {[a, b, Ta, Tb] { return bulletDistance(a.get(), Ta, b.get(), Tb); }, deflection / c.size};
  });
}

}  // namespace dial
