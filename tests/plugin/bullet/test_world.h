// A btDiscreteDynamicsWorld with the plugin registered, owning its shapes and bodies, torn down in the order
// Bullet needs (world, then the registration, then the dispatcher).
#pragma once

#include "unidist/bullet/plugin.h"
#include "unidist/bullet/shapes.h"

#include <btBulletDynamicsCommon.h>

#include <memory>
#include <vector>

namespace bullet_test {

inline btTransform at(double x, double y, double z, const btQuaternion& q = btQuaternion::getIdentity()) {
  return btTransform(q, btVector3(btScalar(x), btScalar(y), btScalar(z)));
}

class TestWorld {
 public:
  TestWorld() {
    plugin = unidist::bullet::registerAlgorithms(&dispatcher);
    world = std::make_unique<btDiscreteDynamicsWorld>(&dispatcher, &broadphase, &solver, &config);
    world->setGravity(btVector3(0, 0, btScalar(-9.81)));
  }
  ~TestWorld() {
    for (auto& b : bodies) world->removeRigidBody(b.get());
    world.reset();
    plugin.reset();
  }

  /// Adds a body (mass 0: static) with the shape's own inertia; the world keeps the shape.
  btRigidBody* add(std::unique_ptr<btCollisionShape> shape, double mass, const btTransform& pose, double friction = 0.6) {
    btVector3 inertia(0, 0, 0);
    if (mass > 0) shape->calculateLocalInertia(btScalar(mass), inertia);
    motions.push_back(std::make_unique<btDefaultMotionState>(pose));
    btRigidBody::btRigidBodyConstructionInfo info(btScalar(mass), motions.back().get(), shape.get(), inertia);
    info.m_friction = btScalar(friction);
    bodies.push_back(std::make_unique<btRigidBody>(info));
    shapes.push_back(std::move(shape));
    world->addRigidBody(bodies.back().get());
    return bodies.back().get();
  }

  void run(double seconds, double dt = 1.0 / 240) {
    const int n = static_cast<int>(seconds / dt + 0.5);
    for (int i = 0; i < n; ++i) world->stepSimulation(btScalar(dt), 1, btScalar(dt));
  }

  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  std::unique_ptr<unidist::bullet::Registration> plugin;
  std::unique_ptr<btDiscreteDynamicsWorld> world;
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btDefaultMotionState>> motions;
  std::vector<std::unique_ptr<btRigidBody>> bodies;
};

}  // namespace bullet_test
