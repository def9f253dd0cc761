// The runners' frame callback (SimOptions::frame), which the pictures draw from: called at step 0, every K-th
// step and the last, with the bodies' poses and that step's touching contacts, in both engines.
#include "unidist/adapters/scene.h"
#include "unidist/bullet/scene_runner.h"
#include "unidist/ode/scene_runner.h"

#include <gtest/gtest.h>

namespace {

struct Frame {
  int step;
  std::vector<unidist::BodyState> bodies;
  std::vector<unidist::SimContact> contacts;
};

TEST(FrameCallback, StepsPosesAndContactsInBothEngines) {
  // A ball 1 cm above a floor: it lands around step 11 of 20.
  const unidist::Scene scene = unidist::parseScene(R"({"dt": 0.004, "steps": 20, "bodies": [
      {"name": "floor", "model": "plane:nx=0,ny=0,nz=1,d=0", "static": true},
      {"name": "ball", "model": "sphere:r=0.1", "pose": [0, 0, 0.11, 1, 0, 0, 0], "mass": 1}]})",
                                                   ".", "drop");
  for (const std::string engine : {"bullet", "ode"}) {
    SCOPED_TRACE(engine);
    std::vector<Frame> frames;
    unidist::SimOptions options;
    options.frameEvery = 6;
    options.frame = [&](int step, const std::vector<unidist::BodyState>& bodies,
                        const std::vector<unidist::SimContact>& contacts) {
      frames.push_back({step, bodies, contacts});
    };
    const unidist::SimResult r =
        engine == "bullet" ? unidist::bullet::runScene(scene, options) : unidist::ode::runScene(scene, options);
    ASSERT_EQ(frames.size(), 5u);
    const int steps[] = {0, 6, 12, 18, 20};
    for (std::size_t i = 0; i < 5; ++i) EXPECT_EQ(frames[i].step, steps[i]);
    EXPECT_TRUE(frames[0].contacts.empty());
    EXPECT_NEAR(frames[0].bodies[1].pose.translation().z(), 0.11, 1e-6);  // the start (Bullet: floats)
    EXPECT_TRUE(frames.back().bodies[1].pose.isApprox(r.bodies[1].pose, 1e-12));
    const std::vector<unidist::SimContact>& last = frames.back().contacts;
    ASSERT_FALSE(last.empty());
    for (const unidist::SimContact& c : last) {
      EXPECT_NEAR(c.point.z(), 0, 2e-3);
      EXPECT_NEAR(std::abs(c.normal.z()), 1, 1e-6);
      EXPECT_LE(c.separation, 0);
    }
  }
}

}  // namespace
