// The plugin under Bullet's multithreaded pipeline (docs/reliability.md, "Parallel worlds"): btCollisionDispatcherMt
// + btDiscreteDynamicsWorldMt with the unidist algorithm registered. Debian's Bullet 3.24 is built without
// BT_THREADSAFE (btCreateDefaultTaskScheduler() returns null, btParallelFor calls the body directly), so this runs
// the Mt classes' code paths — batched manifold creation inside the dispatch, the solver pool — on one thread; it
// must give the same physics as the ordinary world.
#include "plugin/bullet/test_world.h"
#include "plugin/models.h"

#include <BulletCollision/CollisionDispatch/btCollisionDispatcherMt.h>
#include <BulletDynamics/Dynamics/btDiscreteDynamicsWorldMt.h>
#include <LinearMath/btThreads.h>
#include <gtest/gtest.h>

#include <memory>
#include <vector>

namespace {

using bullet_test::at;
using test_models::Vec;
using Rigid = std::vector<std::unique_ptr<btRigidBody>>;

/// The same bodies in either kind of world, through add(shape, mass, pose): a two-footed mesh (two contact
/// regions: the plugin's extra manifolds are created inside the dispatch), a point-cloud box on it and a NURBS
/// ball on the floor.
template <class Add>
void addBodies(Add&& add) {
  add(std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), 0), 0, at(0, 0, 0));
  add(unidist::bullet::makeShape(test_models::twoBoxes(Vec(0.2, 0.3, 0.1), 1.0)), 1, at(0, 0, 0.12));
  add(unidist::bullet::makeShape(test_models::cloudBox(Vec(1.1, 0.3, 0.1))), 1, at(0, 0, 0.31));
  add(unidist::bullet::makeShape(test_models::nurbsSphere(0.3)), 1, at(2, 0, 0.35));
}

std::vector<btVector3> positions(const Rigid& bodies) {
  std::vector<btVector3> out;
  for (const auto& b : bodies) out.push_back(b->getWorldTransform().getOrigin());
  return out;
}

constexpr int kSteps = 480;
constexpr btScalar kDt = btScalar(1.0 / 240);

void stepAll(btDiscreteDynamicsWorld& world) {
  for (int i = 0; i < kSteps; ++i) world.stepSimulation(kDt, 1, kDt);
}

std::vector<btVector3> runOrdinaryWorld() {
  bullet_test::TestWorld w;
  addBodies([&w](std::unique_ptr<btCollisionShape> shape, double mass, const btTransform& pose) {
    w.add(std::move(shape), mass, pose);
  });
  stepAll(*w.world);
  return positions(w.bodies);
}

TEST(BulletMtDispatcher, RunsThePluginLikeTheOrdinaryWorld) {
  // btCollisionDispatcherMt sizes its per-thread arrays from the task scheduler: one must be set first.
  btSetTaskScheduler(btGetSequentialTaskScheduler());
  ASSERT_NE(btGetTaskScheduler(), nullptr);
  EXPECT_EQ(btCreateDefaultTaskScheduler(), nullptr) << "this Bullet has a threaded scheduler: extend this test";

  btDefaultCollisionConfiguration config;
  btCollisionDispatcherMt dispatcher(&config, 1);
  btDbvtBroadphase broadphase;
  btConstraintSolverPoolMt solverPool(2);
  auto plugin = unidist::bullet::registerAlgorithms(&dispatcher);
  // Made as bullet_test::TestWorld::add makes them, into this world; they outlive it.
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btDefaultMotionState>> motions;
  Rigid bodies;
  std::vector<btVector3> mt;
  int regionsHeld = 0;
  {
    btDiscreteDynamicsWorldMt world(&dispatcher, &broadphase, &solverPool, nullptr, &config);
    world.setGravity(btVector3(0, 0, btScalar(-9.81)));
    addBodies([&](std::unique_ptr<btCollisionShape> shape, double mass, const btTransform& pose) {
      btVector3 inertia(0, 0, 0);
      if (mass > 0) shape->calculateLocalInertia(btScalar(mass), inertia);
      motions.push_back(std::make_unique<btDefaultMotionState>(pose));
      btRigidBody::btRigidBodyConstructionInfo info(btScalar(mass), motions.back().get(), shape.get(), inertia);
      info.m_friction = btScalar(0.6);
      bodies.push_back(std::make_unique<btRigidBody>(info));
      shapes.push_back(std::move(shape));
      world.addRigidBody(bodies.back().get());
    });
    stepAll(world);
    mt = positions(bodies);
    for (int m = 0; m < dispatcher.getNumManifolds(); ++m)
      if (dispatcher.getManifoldByIndexInternal(m)->getNumContacts() > 0) ++regionsHeld;
    for (auto& b : bodies) world.removeRigidBody(b.get());
  }
  EXPECT_GT(unidist::bullet::stats(*plugin).localUpdates, 0);
  // Feet on the floor (two manifolds), the cloud box on the feet (two), the ball on the floor (one).
  EXPECT_GE(regionsHeld, 4);
  EXPECT_NEAR(double(mt[1].z()), 0.1, 2e-3) << "two-footed mesh";
  EXPECT_NEAR(double(mt[2].z()), 0.3, 3e-3) << "cloud box on the feet";
  EXPECT_NEAR(double(mt[3].z()), 0.3, 2e-3) << "NURBS ball";
  // Not bitwise: the Mt world hands islands to its solver pool in another order (measured: up to 0.8 mm apart
  // after 2 s, the two-footed mesh and the cloud box settling a little differently; the ball identical).
  const std::vector<btVector3> ordinary = runOrdinaryWorld();
  for (std::size_t i = 0; i < mt.size(); ++i)
    EXPECT_LT(double((mt[i] - ordinary[i]).length()), 2e-3) << "body " << i << " differs from the ordinary world";
}

}  // namespace
