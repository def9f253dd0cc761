// The ODE scene runner on the shared acceptance scenes (NURBS sphere on a plane, torus on a box) and on scenes
// built in code: model-frame poses for bodies whose centre of mass is off the model origin, the record callback,
// and the errors.
#include "unidist/adapters/scene.h"
#include "unidist/ode/scene_runner.h"
#include "unidist/primitives.h"

#include <gtest/gtest.h>

#include <iostream>
#include <string>

namespace {

using Vec = Eigen::Vector3d;

const unidist::BodyState& body(const unidist::SimResult& r, const std::string& name) {
  for (const auto& b : r.bodies)
    if (b.name == name) return b;
  throw std::runtime_error("no body " + name);
}

std::string scenePath(const char* name) { return std::string(UNIDIST_SHARED_DIR) + "/acceptance/scenes/" + name; }

TEST(OdeSceneRunner, NurbsSphereOnPlane) {
  const unidist::Scene scene = unidist::loadScene(scenePath("s1_nurbs_sphere_on_plane.json"));
  const unidist::SimResult r = unidist::ode::runScene(scene);
  const auto& ball = body(r, "ball");
  std::cout << "s1: z = " << ball.pose.translation().z() << " |v| = " << ball.linearVelocity.norm()
            << " max penetration " << r.maxPenetration << " contacts " << r.contacts << " steps/s " << r.stepsPerSecond
            << "\n";
  EXPECT_EQ(r.engine, "ode");
  EXPECT_EQ(r.steps, 1200);
  EXPECT_NEAR(ball.pose.translation().z(), 1.0, 0.005);
  EXPECT_LT(ball.linearVelocity.norm(), 0.05);
  EXPECT_GT(r.contacts, 0);
  EXPECT_LT(r.maxPenetration, 0.05);
}

TEST(OdeSceneRunner, TorusOnBox) {
  const unidist::Scene scene = unidist::loadScene(scenePath("s4_torus_on_box.json"));
  const unidist::SimResult r = unidist::ode::runScene(scene);
  const auto& ring = body(r, "ring");
  std::cout << "s4: z = " << ring.pose.translation().z() << " |v| = " << ring.linearVelocity.norm()
            << " tilt " << std::acos(std::min(1.0, ring.pose.linear()(2, 2))) << " max penetration " << r.maxPenetration
            << " contacts " << r.contacts << " steps/s " << r.stepsPerSecond << "\n";
  EXPECT_NEAR(ring.pose.translation().z(), 0.75, 0.005);
  EXPECT_LT(ring.linearVelocity.norm(), 0.05);
  EXPECT_GT(ring.pose.linear()(2, 2), 1 - 1e-4);  // lying flat
}

/// A box whose model origin is not its centre of mass is reported in its model frame.
TEST(OdeSceneRunner, ReportsModelFramesAndRecords) {
  unidist::Scene scene;
  scene.dt = 1.0 / 240;
  scene.steps = 480;
  unidist::SceneBody floor;
  floor.name = "floor";
  floor.model = std::make_shared<unidist::Plane>(Vec(0, 0, 1), 0);
  floor.isStatic = true;
  scene.bodies.push_back(floor);
  unidist::SceneBody cone;
  cone.name = "cone";
  cone.model = std::make_shared<unidist::Cone>(0.5, 0.5);  // centre of mass a quarter up from the base
  cone.pose.translation() = Vec(0.3, -0.2, 0.6);
  cone.mass = 2;
  scene.bodies.push_back(cone);
  int records = 0, lastStep = 0;
  unidist::SimOptions options;
  options.recordEvery = 100;
  options.record = [&](int step, const std::vector<unidist::BodyState>& states) {
    ++records;
    lastStep = step;
    ASSERT_EQ(states.size(), 2u);
    EXPECT_EQ(states[0].pose.translation(), Vec::Zero());
  };
  const unidist::SimResult r = unidist::ode::runScene(scene, options);
  EXPECT_EQ(records, 5);  // 100, 200, 300, 400 and the last (480)
  EXPECT_EQ(lastStep, 480);
  const auto& c = body(r, "cone");
  EXPECT_NEAR(c.pose.translation().z(), 0.5, 2e-3);  // base on the floor: model origin half a height up
  EXPECT_NEAR(c.pose.translation().x(), 0.3, 1e-3);
  EXPECT_NEAR(c.pose.translation().y(), -0.2, 1e-3);
  EXPECT_GT(r.stepsPerSecond, 0);
}

TEST(OdeSceneRunner, RejectsDynamicHalfSpaceAndMasslessBodies) {
  unidist::Scene scene;
  unidist::SceneBody b;
  b.name = "ground";
  b.model = std::make_shared<unidist::Plane>(Vec(0, 0, 1), 0);
  b.mass = 1;
  scene.bodies.push_back(b);
  EXPECT_THROW(unidist::ode::runScene(scene), unidist::InputError);
  scene.bodies[0].model = std::make_shared<unidist::Sphere>(1);
  scene.bodies[0].mass = 0;
  EXPECT_THROW(unidist::ode::runScene(scene), unidist::InputError);
  // ODE is usable again after a failed run (the runner closed what it opened).
  scene.bodies[0].mass = 1;
  scene.steps = 10;
  EXPECT_NO_THROW(unidist::ode::runScene(scene));
}

}  // namespace
