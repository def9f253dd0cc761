// Many independent worlds at once (docs/reliability.md, "Parallel worlds"): four Bullet and four ODE worlds of the
// demo's mixed scene (NURBS ball, the FCL piano mesh, a point-cloud blob, a torus, a box) stepped concurrently in
// std::threads, sharing one loaded scene (so the models' lazy hierarchies are built by racing threads), must end
// bitwise equal to a single-threaded run of a freshly loaded copy.
#include "unidist/adapters/scene.h"
#include "unidist/bullet/scene_runner.h"
#include "unidist/ode/scene_runner.h"

#include <gtest/gtest.h>
#include <ode/ode.h>

#include <cstring>
#include <exception>
#include <string>
#include <thread>
#include <vector>

namespace {

constexpr int kSteps = 300;  // 1.25 s: the drops, the impacts and the first bounces

bool bitwiseEqual(const unidist::BodyState& a, const unidist::BodyState& b) {
  return std::memcmp(a.pose.matrix().data(), b.pose.matrix().data(), 16 * sizeof(double)) == 0 &&
         std::memcmp(a.linearVelocity.data(), b.linearVelocity.data(), 3 * sizeof(double)) == 0 &&
         std::memcmp(a.angularVelocity.data(), b.angularVelocity.data(), 3 * sizeof(double)) == 0;
}

void expectSameFinalStates(const unidist::SimResult& got, const unidist::SimResult& want, const std::string& what) {
  ASSERT_EQ(got.bodies.size(), want.bodies.size()) << what;
  for (std::size_t i = 0; i < want.bodies.size(); ++i)
    EXPECT_TRUE(bitwiseEqual(got.bodies[i], want.bodies[i]))
        << what << ": " << want.bodies[i].name << " at z " << got.bodies[i].pose.translation().z() << ", want "
        << want.bodies[i].pose.translation().z();
}

TEST(ParallelWorlds, FourBulletAndFourOdeWorldsMatchASingleThreadedRun) {
  unidist::SimOptions options;
  options.steps = kSteps;
  // ODE stays initialised for the whole test: every runner's own dInitODE2/dCloseODE pair nests inside this one.
  ASSERT_TRUE(dInitODE2(0));
  const unidist::Scene shared = unidist::loadScene(UNIDIST_MIXED_SCENE);
  constexpr int kWorlds = 8;  // even: Bullet, odd: ODE
  std::vector<unidist::SimResult> results(kWorlds);
  std::vector<std::string> errors(kWorlds);
  std::vector<std::thread> threads;
  for (int i = 0; i < kWorlds; ++i)
    threads.emplace_back([&, i] {
      try {
        if (i % 2 == 0) {
          results[i] = unidist::bullet::runScene(shared, options);
        } else {
          dAllocateODEDataForThread(dAllocateMaskAll);  // ODE's per-thread data (collision caches)
          results[i] = unidist::ode::runScene(shared, options);
          dCleanupODEAllDataForThread();
        }
      } catch (const std::exception& e) {
        errors[i] = e.what();
      }
    });
  for (std::thread& t : threads) t.join();

  const unidist::Scene fresh = unidist::loadScene(UNIDIST_MIXED_SCENE);
  const unidist::SimResult bullet = unidist::bullet::runScene(fresh, options);
  const unidist::SimResult ode = unidist::ode::runScene(fresh, options);
  dCloseODE();
  for (int i = 0; i < kWorlds; ++i) {
    const std::string what = std::string(i % 2 == 0 ? "Bullet" : "ODE") + " world " + std::to_string(i);
    EXPECT_EQ(errors[i], "") << what;
    expectSameFinalStates(results[i], i % 2 == 0 ? bullet : ode, what);
  }
  // The scene did something: the piano fell onto the floor in both engines.
  EXPECT_LT(bullet.bodies[1].pose.translation().z(), 550);
  EXPECT_LT(ode.bodies[1].pose.translation().z(), 550);
}

}  // namespace
