// Penetration depth of two interpenetrating tori, ours beside FCL, Bullet (GImpact) and ODE on the same
// triangles and poses, and beside the truth.
//
// Two tori (R = 1, r = 0.25, so size 2.5) lie side by side in one plane with their outer rims overlapping by
// δ = 0.01 × size along the line of centres. Where the rims meet both surfaces are locally convex, so the
// smooth tori need exactly δ to separate (moving apart along the line of centres by δ leaves them touching,
// and the rim point of one lies δ deep in the other). The tessellated tori differ from that by the chord
// error; our certified bracket says by how much. The peers answer with per-triangle-pair contacts; the
// largest depth among them is what an engine would use.
//
// usage: unidist_bench_penetration [nu nv]   (default 100 × 50 quads = 10,000 triangles per torus)
#include "core/mesh_fixtures.h"
#include "unidist/distance.h"

#include <BulletCollision/Gimpact/btGImpactCollisionAlgorithm.h>
#include <BulletCollision/Gimpact/btGImpactShape.h>
#include <btBulletCollisionCommon.h>
#include <fcl/narrowphase/collision.h>
#include <ode/ode.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

struct Answer {
  double depth;
  int contacts;
  double ms;
};

Answer fclDepth(const meshfix::Soup& s, double offset) {
  using Model = fcl::BVHModel<fcl::OBBRSSd>;
  auto makeModel = [&] {
    auto m = std::make_shared<Model>();
    std::vector<fcl::Triangle> tris;
    for (const auto& t : s.triangles) tris.emplace_back(t[0], t[1], t[2]);
    m->beginModel();
    m->addSubModel(s.vertices, tris);
    m->endModel();
    return m;
  };
  fcl::CollisionObjectd a(makeModel()), b(makeModel());
  b.setTranslation(fcl::Vector3d(offset, 0, 0));
  b.computeAABB();
  a.computeAABB();
  fcl::CollisionRequestd request(1000000, true);
  fcl::CollisionResultd result;
  const auto t0 = Clock::now();
  fcl::collide(&a, &b, request, result);
  const double ms = msSince(t0);
  std::vector<fcl::Contactd> contacts;
  result.getContacts(contacts);
  double depth = 0;
  for (const auto& c : contacts) depth = std::max(depth, c.penetration_depth);
  return {depth, static_cast<int>(contacts.size()), ms};
}

Answer bulletDepth(const meshfix::Soup& s, double offset) {
  std::vector<btScalar> vertices;
  for (const auto& v : s.vertices)
    for (int k = 0; k < 3; ++k) vertices.push_back(static_cast<btScalar>(v[k]));
  std::vector<int> indices;
  for (const auto& t : s.triangles)
    for (int k = 0; k < 3; ++k) indices.push_back(static_cast<int>(t[k]));
  btTriangleIndexVertexArray array(static_cast<int>(s.triangles.size()), indices.data(), 3 * sizeof(int),
                                   static_cast<int>(s.vertices.size()), vertices.data(), 3 * sizeof(btScalar));
  btGImpactMeshShape shapeA(&array), shapeB(&array);
  shapeA.updateBound();
  shapeB.updateBound();
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher(&config);
  btGImpactCollisionAlgorithm::registerAlgorithm(&dispatcher);
  btDbvtBroadphase broadphase;
  btCollisionWorld world(&dispatcher, &broadphase, &config);
  btCollisionObject a, b;
  a.setCollisionShape(&shapeA);
  b.setCollisionShape(&shapeB);
  btTransform tb;
  tb.setIdentity();
  tb.setOrigin(btVector3(static_cast<btScalar>(offset), 0, 0));
  b.setWorldTransform(tb);
  world.addCollisionObject(&a);
  world.addCollisionObject(&b);
  const auto t0 = Clock::now();
  world.performDiscreteCollisionDetection();
  const double ms = msSince(t0);
  double depth = 0;
  int contacts = 0;
  for (int m = 0; m < dispatcher.getNumManifolds(); ++m) {
    const btPersistentManifold* manifold = dispatcher.getManifoldByIndexInternal(m);
    for (int p = 0; p < manifold->getNumContacts(); ++p) {
      depth = std::max(depth, -static_cast<double>(manifold->getContactPoint(p).getDistance()));
      ++contacts;
    }
  }
  world.removeCollisionObject(&b);
  world.removeCollisionObject(&a);
  return {depth, contacts, ms};
}

Answer odeDepth(const meshfix::Soup& s, double offset) {
  dInitODE2(0);
  std::vector<double> vertices;
  for (const auto& v : s.vertices)
    for (int k = 0; k < 3; ++k) vertices.push_back(v[k]);
  std::vector<dTriIndex> indices;
  for (const auto& t : s.triangles)
    for (int k = 0; k < 3; ++k) indices.push_back(static_cast<dTriIndex>(t[k]));
  dTriMeshDataID data = dGeomTriMeshDataCreate();
  dGeomTriMeshDataBuildDouble(data, vertices.data(), 3 * sizeof(double), static_cast<int>(s.vertices.size()),
                              indices.data(), static_cast<int>(indices.size()), 3 * sizeof(dTriIndex));
  dGeomID a = dCreateTriMesh(nullptr, data, nullptr, nullptr, nullptr);
  dGeomID b = dCreateTriMesh(nullptr, data, nullptr, nullptr, nullptr);
  dGeomSetPosition(b, offset, 0, 0);
  std::vector<dContactGeom> contacts(65535);
  const auto t0 = Clock::now();
  const int n = dCollide(a, b, static_cast<int>(contacts.size()), contacts.data(), sizeof(dContactGeom));
  const double ms = msSince(t0);
  double depth = 0;
  for (int i = 0; i < n; ++i) depth = std::max(depth, static_cast<double>(contacts[i].depth));
  dGeomDestroy(b);
  dGeomDestroy(a);
  dGeomTriMeshDataDestroy(data);
  dCloseODE();
  return {depth, n, ms};
}

}  // namespace

int main(int argc, char** argv) {
  const int nu = argc > 2 ? std::stoi(argv[1]) : 100, nv = argc > 2 ? std::stoi(argv[2]) : 50;
  const double R = 1, r = 0.25, size = 2 * (R + r), delta = 0.01 * size;
  const double offset = 2 * (R + r) - delta;
  const meshfix::Soup soup = meshfix::torus(R, r, nu, nv);
  const unidist::TriangleMesh mesh = meshfix::makeMesh(soup);

  std::printf("two tori, %zu triangles each, rims overlapping by %.4g (truth for the smooth tori: depth %.4g)\n",
              soup.triangles.size(), delta, delta);
  std::printf("%-18s %14s %10s %12s  %s\n", "library", "depth", "contacts", "time (ms)", "bounds / note");

  Eigen::Isometry3d poseB = Eigen::Isometry3d::Identity();
  poseB.translation() = Eigen::Vector3d(offset, 0, 0);
  (void)unidist::distance(mesh, Eigen::Isometry3d::Identity(), mesh, poseB);  // builds the hierarchy once
  const auto t0 = Clock::now();
  const unidist::DistanceResult ours = unidist::distance(mesh, Eigen::Isometry3d::Identity(), mesh, poseB);
  const double oursMs = msSince(t0);
  std::printf("%-18s %14.9f %10d %12.3f  [%.9f, %.9f] %s, normal (%.3f %.3f %.3f)\n", "unidist", -ours.distance, 1,
              oursMs, -ours.upperBound, -ours.lowerBound, unidist::toString(ours.status), ours.normal.x(),
              ours.normal.y(), ours.normal.z());

  const Answer f = fclDepth(soup, offset);
  std::printf("%-18s %14.9f %10d %12.3f  max over triangle-pair contacts\n", "FCL 0.7 OBBRSS", f.depth, f.contacts, f.ms);
  const Answer b = bulletDepth(soup, offset);
  std::printf("%-18s %14.9f %10d %12.3f  max over manifold points\n", "Bullet GImpact", b.depth, b.contacts, b.ms);
  const Answer o = odeDepth(soup, offset);
  std::printf("%-18s %14.9f %10d %12.3f  max over contacts\n", "ODE 0.16 trimesh", o.depth, o.contacts, o.ms);
  return 0;
}
