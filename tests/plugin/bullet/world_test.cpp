// The Bullet plugin in real btDiscreteDynamicsWorlds, checked as a Bullet user would: a NURBS sphere, a mesh
// box, a point-cloud box and a unidist torus dropped on a Bullet plane and on a Bullet box rest at the analytic
// height with no drift; a stack of five mixed bodies stands; a box slides over a tessellated floor without
// bumps; a sphere settles at the bottom of a NURBS bowl; a peg drops through the hole of a mesh block (it is not
// hulled); metres and millimetres behave the same; a fast small sphere does not tunnel through thin walls.
#include "plugin/models.h"
#include "plugin/bullet/test_world.h"
#include "unidist/adapters/scene.h"
#include "unidist/bullet/scene_runner.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using bullet_test::at;
using bullet_test::TestWorld;
using test_models::Vec;
using unidist::bullet::makeShape;

struct Dropped {
  const char* name;
  std::shared_ptr<const unidist::Model> model;
  double restHalfHeight;  // centre above the support when resting
  double size;            // for the 1e-3 × size criterion
  bool canTip;            // a ball may roll: its orientation is free
};

std::vector<Dropped> droppedBodies() {
  return {{"nurbs sphere", test_models::nurbsSphere(0.5), 0.5, 1.0, false},
          {"mesh box", test_models::meshBox(Vec(0.4, 0.3, 0.25)), 0.25, 1.0, true},
          {"cloud box", test_models::cloudBox(Vec(0.4, 0.4, 0.3)), 0.3, 1.0, true},
          {"torus", std::make_shared<unidist::Torus>(0.6, 0.15), 0.15, 1.5, true}};
}

/// Drops the body from 0.3 above its rest height onto a support whose top is at `top`; checks rest and drift.
void expectRests(TestWorld& w, const Dropped& d, double top) {
  btRigidBody* body = w.add(makeShape(d.model), 1.0, at(0.05, -0.02, top + d.restHalfHeight + 0.3));
  w.run(4.0);
  const double z4 = double(body->getWorldTransform().getOrigin().z());
  const btVector3 xy4 = body->getWorldTransform().getOrigin();
  w.run(10.0);
  const btTransform& X = body->getWorldTransform();
  const double z = double(X.getOrigin().z());
  SCOPED_TRACE(d.name);
  EXPECT_NEAR(z, top + d.restHalfHeight, 1e-3 * d.size);
  EXPECT_NEAR(z, z4, 1e-4 * d.size) << "drift over 10 s";
  EXPECT_LT(double((X.getOrigin() - xy4).length()), 1e-3 * d.size) << "sideways drift";
  EXPECT_LT(double(body->getLinearVelocity().length()), 1e-2);
  if (d.canTip) {
    EXPECT_NEAR(double(X.getBasis().getColumn(2).z()), 1.0, 1e-4) << "tipped over";
  }
}

TEST(BulletWorld, EachModelRestsOnABulletPlane) {
  for (const Dropped& d : droppedBodies()) {
    TestWorld w;
    w.add(std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), 0), 0, at(0, 0, 0));
    expectRests(w, d, 0);
  }
}

TEST(BulletWorld, EachModelRestsOnABulletBox) {
  for (const Dropped& d : droppedBodies()) {
    TestWorld w;
    w.add(std::make_unique<btBoxShape>(btVector3(2, 2, 0.5)), 0, at(0, 0, 0.5));
    expectRests(w, d, 1.0);
  }
}

TEST(BulletWorld, EachModelRestsOnAUnidistMeshBox) {
  for (const Dropped& d : droppedBodies()) {
    TestWorld w;
    w.add(makeShape(test_models::meshBox(Vec(2, 2, 0.5))), 0, at(0, 0, 0.5));
    expectRests(w, d, 1.0);
  }
}

TEST(BulletWorld, StackOfFiveMixedBodiesStands) {
  TestWorld w;
  w.add(std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), 0), 0, at(0, 0, 0));
  const Vec slab(1.2, 1.2, 0.25);
  btRigidBody* mesh = w.add(makeShape(test_models::meshBox(slab)), 2, at(0, 0, 0.26));
  btRigidBody* cloud = w.add(makeShape(test_models::cloudBox(slab)), 2, at(0, 0, 0.77));
  btRigidBody* box = w.add(makeShape(std::make_shared<unidist::Box>(slab)), 2, at(0, 0, 1.28));
  btRigidBody* torus = w.add(makeShape(std::make_shared<unidist::Torus>(1, 0.25)), 1, at(0, 0, 1.77));
  btRigidBody* ball = w.add(makeShape(test_models::nurbsSphere(0.3)), 1, at(0, 0, 1.9));
  w.run(6.0);
  // Each slab 0.5 thick; the torus (tube 0.25) on the top slab; the NURBS ball (r 0.3) in the ring's hole (inner
  // radius 0.75) on the top slab too.
  const double expected[5] = {0.25, 0.75, 1.25, 1.75, 1.8};
  btRigidBody* bodies[5] = {mesh, cloud, box, torus, ball};
  for (int i = 0; i < 5; ++i) {
    const btVector3 p = bodies[i]->getWorldTransform().getOrigin();
    EXPECT_NEAR(double(p.z()), expected[i], 3e-3) << "body " << i;
    // The ball may roll about inside the ring's hole (radius 0.75 − 0.3); the rest stay centred.
    EXPECT_LT(std::hypot(double(p.x()), double(p.y())), i == 4 ? 0.45 : 1e-2) << "body " << i;
  }
}

/// A box pushed at 4 m/s over a floor that is added first (so the floor is the pair's first body).
void expectSmoothSlide(std::unique_ptr<btCollisionShape> floor, double floorZ, const char* what) {
  TestWorld w;
  w.add(std::move(floor), 0, at(0, 0, floorZ));
  btRigidBody* box = w.add(makeShape(std::make_shared<unidist::Box>(Vec(0.25, 0.25, 0.25))), 1, at(-6, 0.13, 0.25), 0.2);
  w.run(0.5);
  box->setLinearVelocity(btVector3(4, 0.5, 0));
  box->activate(true);
  double worstVz = 0, worstZ = 0;
  const double dt = 1.0 / 240;
  for (int i = 0; i < 480; ++i) {
    w.world->stepSimulation(btScalar(dt), 1, btScalar(dt));
    worstVz = std::max(worstVz, std::abs(double(box->getLinearVelocity().z())));
    worstZ = std::max(worstZ, std::abs(double(box->getWorldTransform().getOrigin().z()) - 0.25));
  }
  SCOPED_TRACE(what);
  EXPECT_GT(double(box->getWorldTransform().getOrigin().x()), -4.0) << "it slid";
  EXPECT_LT(worstVz, 0.02) << "bumps";
  EXPECT_LT(worstZ, 2e-3);
}

TEST(BulletWorld, BoxSlidesOverATessellatedFloorWithoutBumps) {
  expectSmoothSlide(makeShape(test_models::tessellatedFloor(10, 40)), 0, "open mesh floor, 3200 triangles");
  expectSmoothSlide(makeShape(std::make_shared<unidist::Box>(Vec(10, 10, 0.5))), -0.5, "unidist box floor");
}

TEST(BulletWorld, SphereSettlesAtTheBottomOfANurbsBowl) {
  TestWorld w;
  w.add(makeShape(test_models::nurbsBowl(2)), 0, at(0, 0, 2));  // bottom at z = 0
  btRigidBody* ball = w.add(makeShape(std::make_shared<unidist::Sphere>(0.5)), 1, at(0.6, 0.2, 1.2));
  ball->setDamping(0.6, 0.6);  // so that the rolling dies out within the test
  ball->setSleepingThresholds(0.01f, 0.01f);  // Bullet's defaults put a slowly rocking ball to sleep mid-swing
  w.run(12.0);
  const btVector3 p = ball->getWorldTransform().getOrigin();
  EXPECT_NEAR(double(p.z()), 0.5, 5e-3);
  EXPECT_LT(std::hypot(double(p.x()), double(p.y())), 0.05);
}

TEST(BulletWorld, PegDropsThroughTheHoleOfAMeshBlock) {
  TestWorld w;
  w.add(std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), 0), 0, at(0, 0, 0));
  w.add(makeShape(test_models::blockWithHole(1, 0.3, 1)), 0, at(0, 0, 0));
  btRigidBody* peg = w.add(makeShape(std::make_shared<unidist::Box>(Vec(0.2, 0.2, 0.6))), 1, at(0.02, 0, 1.9));
  w.run(3.0);
  const btVector3 p = peg->getWorldTransform().getOrigin();
  EXPECT_NEAR(double(p.z()), 0.6, 3e-3) << "the peg stands on the floor inside the hole, not on a hull";
  EXPECT_LT(std::abs(double(p.x())), 0.1);
}

TEST(BulletWorld, SeparateContactRegionsGetTheirOwnManifolds) {
  TestWorld w;
  w.add(std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), 0), 0, at(0, 0, 0));
  btRigidBody* feet = w.add(makeShape(test_models::twoBoxes(Vec(0.2, 0.3, 0.1), 1.0)), 1, at(0, 0, 0.15));
  w.run(2.0);
  int manifolds = 0, points = 0;
  for (int m = 0; m < w.dispatcher.getNumManifolds(); ++m) {
    const btPersistentManifold* mf = w.dispatcher.getManifoldByIndexInternal(m);
    if (mf->getNumContacts() == 0) continue;
    ++manifolds;
    points += mf->getNumContacts();
  }
  EXPECT_EQ(manifolds, 2) << "one per foot";
  EXPECT_EQ(points, 8) << "each foot's four corners";
  EXPECT_NEAR(double(feet->getWorldTransform().getOrigin().z()), 0.1, 1e-3);
  EXPECT_NEAR(double(feet->getWorldTransform().getBasis().getColumn(2).z()), 1.0, 1e-4);
}

/// The NURBS sphere dropped on a plane in a world scaled by `unit` (1: metres, 1000: millimetres).
double restHeightAtScale(double unit) {
  unidist::Scene s;
  s.gravity = Vec(0, 0, -9.81 * unit);
  s.dt = 1.0 / 240;
  s.steps = 960;
  unidist::SceneBody floor, ball;
  floor.name = "floor";
  floor.model = std::make_shared<unidist::Plane>(Vec(0, 0, 1), 0);
  floor.isStatic = true;
  ball.name = "ball";
  ball.model = test_models::nurbsSphere(0.5 * unit);
  ball.mass = 1;
  ball.pose.translation() = Vec(0.1 * unit, 0, 0.8 * unit);
  s.bodies = {floor, ball};
  return unidist::bullet::runScene(s).bodies[1].pose.translation().z() / unit;
}

TEST(BulletWorld, MetresAndMillimetresBehaveTheSame) {
  const double metres = restHeightAtScale(1), millimetres = restHeightAtScale(1000);
  EXPECT_NEAR(metres, 0.5, 1e-3);
  EXPECT_NEAR(millimetres, 0.5, 1e-3);
  EXPECT_NEAR(metres, millimetres, 1e-3);
}

/// A sphere of radius 0.05 shot at 60 m/s (0.25 per step, five times its size) at a wall at x = 0.
void expectNoTunnelling(std::unique_ptr<btCollisionShape> wall, const char* what) {
  TestWorld w;
  w.world->setGravity(btVector3(0, 0, 0));
  w.add(std::move(wall), 0, at(0, 0, 0));
  btRigidBody* ball = w.add(makeShape(std::make_shared<unidist::Sphere>(0.05)), 0.1, at(-2, 0, 0));
  ball->setLinearVelocity(btVector3(60, 0, 0));
  w.run(0.2);
  EXPECT_LT(double(ball->getWorldTransform().getOrigin().x()), 0.0) << what << ": the ball went through";
}

TEST(BulletWorld, FastSmallSphereDoesNotTunnelThroughThinWalls) {
  expectNoTunnelling(makeShape(test_models::meshBox(Vec(0.01, 1, 1))), "mesh wall");
  expectNoTunnelling(makeShape(test_models::nurbsWall(1)), "NURBS wall");
}

}  // namespace
