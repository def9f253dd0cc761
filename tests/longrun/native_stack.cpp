// unidist_native_stack: the long-run stack (tests/longrun/stack.json) built from Bullet's own shapes, stepped with
// the settings of unidist::bullet::runScene — the reference the plugin is measured against (docs/reliability.md,
// "Long runs"). Slabs are btBoxShapes (the mesh slab optionally a btConvexHullShape), the ball a btSphereShape.
// The cloud slab's pocket (the ball cradled by four lattice points 60 mm apart) is a box with four 0.5 mm
// spheres on top, so that the ball touches only them, as it touches only four cloud points in the plugin's scene.
//
//   unidist_native_stack [--steps N] [--flat | --no-ball] [--hull] [--split-threshold T]
// --flat: the ball on the bare box top; --no-ball: the slabs alone; --split-threshold: Bullet's
// m_splitImpulsePenetrationThreshold (default: the runner's, -0.02 x the smallest dynamic diagonal; Bullet's own
// default is -0.04).
// Prints each body's largest sideways drift after 10 s every 50 s and the step the stack order was lost, if it was.
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

extern bool gDisableDeactivation;  // btRigidBody.cpp

int main(int argc, char** argv) {
  int steps = 100000;
  bool flat = false, hull = false, ball = true;
  double threshold = -0.02 * std::sqrt(3 * 160.0 * 160);  // the runner's: the cone's bounding box is 160 x 160 x 160
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--steps") && i + 1 < argc) steps = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--flat")) flat = true;
    else if (!std::strcmp(argv[i], "--hull")) hull = true;
    else if (!std::strcmp(argv[i], "--no-ball")) ball = false;
    else if (!std::strcmp(argv[i], "--split-threshold") && i + 1 < argc) threshold = std::atof(argv[++i]);
    else {
      std::fprintf(stderr, "usage: unidist_native_stack [--steps N] [--flat | --no-ball] [--hull] "
                           "[--split-threshold T]\n");
      return 2;
    }
  }
  gDisableDeactivation = true;  // as unidist_longrun: a sleeping stack tests nothing
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher(&config);
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &config);
  world.setGravity(btVector3(0, 0, -9810));
  world.getSolverInfo().m_splitImpulsePenetrationThreshold = btScalar(threshold);
  const double dt = 1.0 / 240;

  btStaticPlaneShape floorShape(btVector3(0, 0, 1), 0);
  btBoxShape box600(btVector3(300, 300, 30)), box450(btVector3(225, 225, 30)), box360(btVector3(180, 180, 30));
  btConvexHullShape meshHull;
  for (int i = 0; i < 8; ++i) meshHull.addPoint(btVector3(i & 1 ? 300 : -300, i & 2 ? 300 : -300, i & 4 ? 30 : -30));
  meshHull.setMargin(0);
  meshHull.initializePolyhedralFeatures();
  // Lattice points at (0|60, 0|60) on the top face, raised 6.6 mm: the ball (its bottom 6.1 mm below the points'
  // plane when cradled) clears the face by 0.5 mm.
  const double lift = 6.6;
  btSphereShape knob(0.5), sphere(150);
  btCompoundShape pocket;
  btTransform t = btTransform::getIdentity();
  pocket.addChildShape(t, &box360);
  for (int i = 0; i < 4; ++i) {
    t.setOrigin(btVector3(i & 1 ? 60 : 0, i & 2 ? 60 : 0, btScalar(30 + lift - 0.5)));
    pocket.addChildShape(t, &knob);
  }
  btCylinderShapeZ cylinder(btVector3(80, 80, 100));  // cylinder:r=80,h=100 (half height), cone:r=80,h=80 likewise
  btConeShapeZ cone(80, 160);
  const double ballZ = (flat ? 330 : 180 + lift + std::sqrt(150.0 * 150 - 2 * 30 * 30)) + 1.1;
  struct Body { const char* name; btCollisionShape* shape; double mass; btVector3 origin; };
  std::vector<Body> bodies = {
      {"mesh_slab", hull ? static_cast<btCollisionShape*>(&meshHull) : &box600, 12, btVector3(0, 0, 31)},
      {"box_slab", &box450, 9, btVector3(0, 0, 92)},
      {"cloud_slab", flat ? static_cast<btCollisionShape*>(&box360) : &pocket, 6, btVector3(0, 0, 153)},
      {"ball", &sphere, 14, btVector3(30, 30, btScalar(ballZ))},
      {"cylinder", &cylinder, 5, btVector3(700, 0, 101)},
      {"cone", &cone, 3, btVector3(-700, 300, 81)}};
  if (!ball) bodies.erase(bodies.begin() + 3);
  btRigidBody floorBody(0, nullptr, &floorShape);
  floorBody.setFriction(0.6);
  world.addRigidBody(&floorBody);
  std::vector<std::unique_ptr<btRigidBody>> rigid;
  for (const Body& b : bodies) {
    btVector3 inertia;
    b.shape->calculateLocalInertia(btScalar(b.mass), inertia);
    btRigidBody::btRigidBodyConstructionInfo info(btScalar(b.mass), nullptr, b.shape, inertia);
    info.m_startWorldTransform.setOrigin(b.origin);
    info.m_friction = 0.6;
    rigid.push_back(std::make_unique<btRigidBody>(info));
    world.addRigidBody(rigid.back().get());
  }
  const int settle = 2400;  // 10 s, as unidist_longrun
  std::vector<btVector3> settled(rigid.size());
  std::vector<double> drift(rigid.size(), 0);
  int lost = -1;
  auto z = [&](int i) { return double(rigid[i]->getWorldTransform().getOrigin().z()); };
  for (int s = 1; s <= steps; ++s) {
    world.stepSimulation(btScalar(dt), 1, btScalar(dt));
    for (std::size_t i = 0; i < rigid.size(); ++i) {
      btVector3 move = rigid[i]->getWorldTransform().getOrigin() - settled[i];
      if (s == settle) settled[i] = rigid[i]->getWorldTransform().getOrigin();
      if (s > settle) drift[i] = std::max(drift[i], std::hypot(double(move.x()), double(move.y())));
    }
    // slabs in order, the ball above the cloud slab's top (its centre 6 mm below that when cradled: 100 is far)
    if (lost < 0 && (z(1) < z(0) || z(2) < z(1) || (ball && z(3) < z(2) + 100))) lost = s;
    if (s % 12000 == 0 || s == steps) {
      std::printf("step %6d (%5.1f s) drift after 10 s:", s, s * dt);
      for (std::size_t i = 0; i < rigid.size(); ++i) std::printf(" %s %.4g", bodies[i].name, drift[i]);
      std::printf("  order %s\n", lost < 0 ? "kept" : ("lost at step " + std::to_string(lost)).c_str());
      std::fflush(stdout);
    }
  }
  for (auto& r : rigid) world.removeRigidBody(r.get());
  world.removeRigidBody(&floorBody);
  return lost < 0 ? 0 : 1;
}
