// Bullet plugin throughput: steps per second of a btDiscreteDynamicsWorld with the plugin registered, for
// (1) 50 mixed unidist bodies (sphere and box primitives, mesh boxes, point-cloud boxes, cylinders, capsules)
// dropped in a pile on a btStaticPlaneShape, and (2) a 50-box pile once as unidist box primitives and once as
// Bullet's native btBoxShape (Bullet's box–box and convex–plane algorithms), same poses, same world settings.
// Each configuration runs `runs` times (the two box piles interleaved, so that both see the same machine load); the
// median steps/s is reported with the ratio native / unidist.
// Usage: unidist_bench_bullet [steps=600] [runs=3] [boxes]   (CSV on stdout; "boxes": the box piles only)
#include "median.h"
#include "plugin/models.h"
#include "unidist/bullet/plugin.h"
#include "unidist/bullet/shapes.h"
#include "unidist/mesh.h"
#include "unidist/point_cloud.h"
#include "unidist/primitives.h"

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace {

using Vec = Eigen::Vector3d;
using ModelPtr = std::shared_ptr<const unidist::Model>;

/// A box [-h, h]^3 as a 12-triangle mesh and as the lattice of its faces (a point cloud).
ModelPtr meshBox(double h) { return test_models::meshBox(Vec(h, h, h), 1); }
ModelPtr cloudBox(double h) { return test_models::cloudBox(Vec(h, h, h), 4); }

/// Pile positions: a 5 × 5 grid, two layers, slightly staggered so that bodies meet at edges and faces.
btVector3 slot(int i) {
  return btVector3(btScalar(0.6 * (i % 5) + 0.05 * (i / 25)), btScalar(0.6 * ((i / 5) % 5)), btScalar(0.3 + 0.7 * (i / 25)));
}

/// Steps per second of a world holding the given shapes (mass 1) above a plane.
double stepsPerSecond(const std::function<std::unique_ptr<btCollisionShape>(int)>& shapeOf, int bodies, int steps) {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher(&config);
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  auto plugin = unidist::bullet::registerAlgorithms(&dispatcher);
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btDefaultMotionState>> motions;
  std::vector<std::unique_ptr<btRigidBody>> rigid;
  double seconds = 0;
  {
    btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &config);
    world.setGravity(btVector3(0, 0, btScalar(-9.81)));
    auto add = [&](std::unique_ptr<btCollisionShape> s, double mass, const btVector3& at) {
      btVector3 inertia(0, 0, 0);
      if (mass > 0) s->calculateLocalInertia(btScalar(mass), inertia);
      motions.push_back(std::make_unique<btDefaultMotionState>(btTransform(btQuaternion::getIdentity(), at)));
      rigid.push_back(std::make_unique<btRigidBody>(btScalar(mass), motions.back().get(), s.get(), inertia));
      shapes.push_back(std::move(s));
      world.addRigidBody(rigid.back().get());
    };
    add(std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), 0), 0, btVector3(0, 0, 0));
    for (int i = 0; i < bodies; ++i) add(shapeOf(i), 1, slot(i));
    const auto start = std::chrono::steady_clock::now();
    for (int s = 0; s < steps; ++s) world.stepSimulation(btScalar(1.0 / 240), 1, btScalar(1.0 / 240));
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    for (auto& b : rigid) world.removeRigidBody(b.get());
  }
  return steps / seconds;
}

}  // namespace

int main(int argc, char** argv) {
  const int steps = argc > 1 ? std::atoi(argv[1]) : 600;
  const int runs = argc > 2 ? std::atoi(argv[2]) : 3;
  const std::vector<ModelPtr> mixed = {std::make_shared<unidist::Sphere>(0.25), std::make_shared<unidist::Box>(Vec(0.2, 0.2, 0.2)),
                                       meshBox(0.2), cloudBox(0.2), std::make_shared<unidist::Cylinder>(0.2, 0.2),
                                       std::make_shared<unidist::Capsule>(0.15, 0.1)};
  const ModelPtr box = std::make_shared<unidist::Box>(Vec(0.25, 0.25, 0.25));
  const bool boxesOnly = argc > 3 && std::string(argv[3]) == "boxes";
  std::vector<double> mixedRuns{0}, unidistRuns, nativeRuns;
  for (int k = 0; k < runs; ++k) {
    if (!boxesOnly)
      mixedRuns.push_back(stepsPerSecond([&](int i) { return unidist::bullet::makeShape(mixed[std::size_t(i) % mixed.size()]); },
                                         50, steps));
    unidistRuns.push_back(stepsPerSecond([&](int) { return unidist::bullet::makeShape(box); }, 50, steps));
    nativeRuns.push_back(stepsPerSecond([](int) { return std::make_unique<btBoxShape>(btVector3(0.25, 0.25, 0.25)); }, 50, steps));
  }
  if (!boxesOnly) mixedRuns.erase(mixedRuns.begin());
  const double mixedRate = median(mixedRuns), unidistBoxes = median(unidistRuns), nativeBoxes = median(nativeRuns);
  std::printf("case,steps_per_second\n");
  if (!boxesOnly) std::printf("50 mixed unidist bodies,%.1f\n", mixedRate);
  std::printf("50 boxes unidist,%.1f\n", unidistBoxes);
  std::printf("50 boxes bullet native,%.1f\n", nativeBoxes);
  std::printf("ratio native/unidist,%.2f\n", nativeBoxes / unidistBoxes);
  return 0;
}
