// unidist_longrun: a scene of mixed bodies stacked and resting (default tests/longrun/stack.json: a mesh slab, a
// box, a point-cloud slab and a NURBS ball in a pocket of the cloud's lattice, a cylinder and a cone beside them)
// stepped N times by the Bullet and/or ODE scene runner, then once more in the same process. Checks the bounds of
// trajectory_monitor.h every step, the engine's deepest contact, RSS growth after settling and a bitwise-equal
// rerun; prints the numbers; exits 1 on any violation, 2 on bad usage (docs/reliability.md, "Long runs").
//
//   unidist_longrun [--engine bullet|ode|both] [--steps N] [--scene FILE] [--settle STEP] [--no-rerun]
#include "rss.h"
#include "trajectory_monitor.h"
#include "unidist/bullet/scene_runner.h"
#include "unidist/ode/scene_runner.h"

#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

namespace {

using unidist::BodyState;
using unidist::Scene;

struct Args {
  std::string engine = "both";
  int steps = 100000;
  std::string scene = UNIDIST_LONGRUN_SCENE;
  int settle = -1;  // < 0: min(2400, steps / 2)
  bool rerun = true;
};

/// Growth of the resident set allowed between the settle step and the end (a leak of 40 bytes a step over
/// 100,000 steps is 3.8 MiB).
constexpr long kRssGrowthBoundKiB = 4096;

struct Run {
  unidist::SimResult result;
  long rssSettledKiB = -1, rssEndKiB = -1;
};

std::vector<BodyState> initialStates(const Scene& scene) {
  std::vector<BodyState> out;
  for (const unidist::SceneBody& b : scene.bodies) {
    BodyState s;
    s.name = b.name;
    s.pose = b.pose;
    if (!b.isStatic) s.linearVelocity = b.linearVelocity, s.angularVelocity = b.angularVelocity;
    out.push_back(s);
  }
  return out;
}

Run runOnce(const std::string& engine, const Scene& scene, int steps, int settle, longrun::TrajectoryMonitor& monitor) {
  Run run;
  monitor.observe(0, initialStates(scene));
  unidist::SimOptions options;
  options.steps = steps;
  options.recordEvery = 1;
  options.record = [&](int step, const std::vector<BodyState>& bodies) {
    monitor.observe(step, bodies);
    if (step == settle) run.rssSettledKiB = longrun::residentKiB();
    if (step == steps) run.rssEndKiB = longrun::residentKiB();
  };
  run.result = engine == "bullet" ? unidist::bullet::runScene(scene, options) : unidist::ode::runScene(scene, options);
  return run;
}

/// First step whose fingerprint differs between the two runs, or -1.
int firstDifference(const std::vector<std::uint64_t>& a, const std::vector<std::uint64_t>& b) {
  const std::size_t n = std::min(a.size(), b.size());
  for (std::size_t i = 0; i < n; ++i)
    if (a[i] != b[i]) return static_cast<int>(i);
  return a.size() == b.size() ? -1 : static_cast<int>(n);
}

bool bitwiseEqual(const std::vector<BodyState>& a, const std::vector<BodyState>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::memcmp(a[i].pose.matrix().data(), b[i].pose.matrix().data(), 16 * sizeof(double)) != 0) return false;
  return true;
}

double smallestDynamicDiagonal(const Scene& scene) {
  double d = 1e300;
  for (const unidist::SceneBody& b : scene.bodies)
    if (!b.isStatic) d = std::min(d, b.model->localBounds().diagonal());
  return d;
}

/// Runs one engine (twice unless --no-rerun), prints the numbers, returns the violations.
std::vector<std::string> checkEngine(const std::string& engine, const Scene& scene, const Args& args) {
  longrun::Bounds bounds;
  bounds.settleStep = args.settle >= 0 ? args.settle : std::min(2400, args.steps / 2);
  longrun::TrajectoryMonitor monitor(scene, bounds, args.steps);
  const Run first = runOnce(engine, scene, args.steps, bounds.settleStep, monitor);
  std::vector<std::string> violations = monitor.violations();

  std::printf("== %s: %s, %d steps of %.6g s (%.1f s simulated), settled from step %d\n", engine.c_str(),
              scene.path.c_str(), args.steps, scene.dt, args.steps * scene.dt, bounds.settleStep);
  std::printf("steps/s           %.0f\n", first.result.stepsPerSecond);
  std::printf("non-finite        %s\n", monitor.firstNonFiniteStep < 0 ? "none" : "YES");
  std::printf("ground clearance  min over the run, per body (allowance):");
  for (std::size_t i = 0; i < scene.bodies.size(); ++i)
    if (!scene.bodies[i].isStatic)
      std::printf(" %s %.4g (-%.3g)", scene.bodies[i].name.c_str(), monitor.minGroundClearance[i],
                  monitor.groundAllowance[i]);
  std::printf("\nsideways drift    max after settling, per body:");
  for (std::size_t i = 0; i < scene.bodies.size(); ++i)
    if (!scene.bodies[i].isStatic)
      std::printf(" %s %.4g", scene.bodies[i].name.c_str(), monitor.maxDriftAfterSettling[i]);
  std::printf("\nstacked pairs     %zu, min gap between their lowest points %.4g (must stay > 0)\n",
              monitor.stackedPairs().size(), monitor.minStackGap);
  std::printf("energy            E(0) %.6g, E(settled) %.6g, max E-E(0) %.4g, max E-E(settled) %.4g (bound %.4g)\n",
              monitor.initialEnergy, monitor.settledEnergy, monitor.maxExcessOverInitial,
              monitor.maxExcessAfterSettling, monitor.energyBound);
  const double penetrationBound = bounds.penetrationAllowance * smallestDynamicDiagonal(scene);
  std::printf("deepest contact   %.4g (bound %.4g)\n", first.result.maxPenetration, penetrationBound);
  if (!(first.result.maxPenetration <= penetrationBound))
    violations.push_back("deepest contact " + std::to_string(first.result.maxPenetration) + " beyond " +
                         std::to_string(penetrationBound));
  const long growth = first.rssEndKiB - first.rssSettledKiB;
  std::printf("RSS               settled %ld KiB, end %ld KiB, growth %ld KiB (bound %ld KiB)\n", first.rssSettledKiB,
              first.rssEndKiB, growth, kRssGrowthBoundKiB);
  if (first.rssSettledKiB < 0 || first.rssEndKiB < 0 || growth > kRssGrowthBoundKiB)
    violations.push_back("RSS grew by " + std::to_string(growth) + " KiB after settling");

  if (args.rerun) {
    longrun::TrajectoryMonitor again(scene, bounds, args.steps);
    const Run second = runOnce(engine, scene, args.steps, bounds.settleStep, again);
    const int diff = firstDifference(monitor.fingerprints(), again.fingerprints());
    const bool same = diff < 0 && bitwiseEqual(first.result.bodies, second.result.bodies);
    if (same)
      std::printf("determinism       rerun bitwise equal at all %zu steps (rerun %.0f steps/s)\n",
                  monitor.fingerprints().size(), second.result.stepsPerSecond);
    else
      std::printf("determinism       rerun DIFFERS, first at step %d\n", diff);
    if (!same) violations.push_back("the rerun's trajectory differs from step " + std::to_string(diff));
  }
  std::printf("final heights    ");
  for (const BodyState& s : first.result.bodies) std::printf(" %s %.4f", s.name.c_str(), s.pose.translation().z());
  std::printf("\n");
  for (const std::string& v : violations) std::printf("VIOLATION         %s\n", v.c_str());
  std::printf("result            %s\n", violations.empty() ? "PASS" : "FAIL");
  std::fflush(stdout);
  return violations;
}

bool parse(int argc, char** argv, Args& args) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool hasValue = i + 1 < argc;
    if (a == "--engine" && hasValue) args.engine = argv[++i];
    else if (a == "--steps" && hasValue) args.steps = std::atoi(argv[++i]);
    else if (a == "--scene" && hasValue) args.scene = argv[++i];
    else if (a == "--settle" && hasValue) args.settle = std::atoi(argv[++i]);
    else if (a == "--no-rerun") args.rerun = false;
    else return false;
  }
  return args.steps > 0 && (args.engine == "bullet" || args.engine == "ode" || args.engine == "both");
}

}  // namespace

int main(int argc, char** argv) {
  Args args;
  if (!parse(argc, argv, args)) {
    std::fprintf(stderr, "usage: unidist_longrun [--engine bullet|ode|both] [--steps N>0] [--scene FILE] "
                         "[--settle STEP] [--no-rerun]\n");
    return 2;
  }
  // Bullet puts bodies at rest to sleep after 2 s, and a sleeping body is neither collided nor integrated: the
  // run would test nothing. Keep every body awake, as ODE's runner does (no auto-disable).
  gDisableDeactivation = true;
  try {
    const Scene scene = unidist::loadScene(args.scene);
    bool failed = false;
    for (const char* engine : {"bullet", "ode"})
      if (args.engine == "both" || args.engine == engine) failed = !checkEngine(engine, scene, args).empty() || failed;
    return failed ? 1 : 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "unidist_longrun: %s\n", e.what());
    return 1;
  }
}
