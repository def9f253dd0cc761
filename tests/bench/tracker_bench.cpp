// Tracker update time beside the cold query (issue 10): a ball over a torus on a recorded haptic-rate trajectory
// (into and out of contact), NURBS – NURBS, NURBS – mesh and mesh – mesh (~20k triangles each), with the global
// pass inline (its cost shows in the updates that run it) and on a worker thread. The cold query is
// unidist::contacts() at the cutoff on the same poses (every k-th, it is slow), which also checks the tracker:
// a miss is a sampled step where the deepest tracked minimum is not the global minimum within 1e-5.
// Usage: unidist_bench_tracker [updates per run, default 2000]. Prints CSV on stdout.
#include "unidist/contacts.h"
#include "unidist/mesh.h"
#include "unidist/nurbs.h"
#include "unidist/tracker.h"

#include "bench/median.h"
#include "core/mesh_fixtures.h"
#include "core/nurbs_fixtures.h"
#include "core/tracker_trajectory.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

namespace {

using unidist::Model;
using Iso = Eigen::Isometry3d;
using tracker_trajectory::kBall;
using tracker_trajectory::kR;
using tracker_trajectory::kTube;

double microsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
}

std::shared_ptr<const Model> mesh(const meshfix::Soup& s) {
  auto m = std::make_shared<unidist::TriangleMesh>(s.vertices, s.triangles);
  m->buildStructures();  // outside the timing, as a haptic application would before its loop
  return m;
}

std::size_t triangles(const Model& m) {
  const auto* t = dynamic_cast<const unidist::TriangleMesh*>(&m);
  return t ? t->triangles().size() : 0;
}

struct Family {
  const char* name;
  std::shared_ptr<const Model> ball, torus;
};

void run(const Family& f, unidist::GlobalPassMode mode, int updates) {
  tracker_trajectory::Trajectory tr;
  tr.steps = updates;
  tr.sweep = 2 * M_PI * updates / 2000.0;  // the same speed for any count: ~1e-3 of the torus per update
  tr.seed = 11;
  const std::vector<Iso> poses = tr.poses();
  unidist::TrackerOptions o;
  o.cutoff = 0.05;
  o.stiffness = 100;
  o.globalPass = mode;
  unidist::Tracker tracker(f.ball, f.torus, o);
  unidist::ContactOptions co;
  co.margin = o.cutoff;
  co.tolerance = tracker.options().tolerance;  // the tracker's own accuracy: the same work
  const int coldEvery = std::max(1, updates / 100);
  std::vector<double> times, local, cold;  // local: updates that neither ran nor merged a pass
  int checked = 0, misses = 0;
  double first = 0;
  for (int i = 0; i < updates; ++i) {
    const Iso& X = poses[static_cast<std::size_t>(i)];
    const auto t0 = std::chrono::steady_clock::now();
    const unidist::TrackerUpdate& u = tracker.update(X, Iso::Identity());
    const double us = microsSince(t0);
    if (i == 0) first = us;  // the synchronous first pass: not a servo update
    else times.push_back(us);
    if (i > 0 && !(mode == unidist::GlobalPassMode::Inline && u.globalPassStarted) && !u.globalPassMerged)
      local.push_back(us);
    if (i % coldEvery != 0) continue;
    const auto t1 = std::chrono::steady_clock::now();
    const std::vector<unidist::Contact> ref = unidist::contacts(*f.ball, X, *f.torus, Iso::Identity(), co);
    cold.push_back(microsSince(t1));
    if (ref.empty() || ref.front().distance > o.cutoff - 1e-5) continue;
    ++checked;
    const double tracked = tracker.minima().empty() ? INFINITY : tracker.minima().front().distance;
    misses += std::abs(tracked - ref.front().distance) > 1e-5 ? 1 : 0;
  }
  tracker.waitForGlobalPass();
  const unidist::TrackerCounters& c = tracker.counters();
  std::printf("%s,%s,%zu,%zu,%d,%.1f,%.1f,%.1f,%.1f,%.1f,%.1f,%ld,%.2f,%zu,%.1f,%.1f,%d,%d\n", f.name,
              mode == unidist::GlobalPassMode::Inline ? "inline" : "background", triangles(*f.ball),
              triangles(*f.torus), updates, median(times), quantile(times, 0.99),
              *std::max_element(times.begin(), times.end()), quantile(local, 0.99),
              *std::max_element(local.begin(), local.end()), first, c.globalPasses,
              static_cast<double>(c.newtonIterations + c.localSteps) / updates, cold.size(), median(cold),
              quantile(cold, 0.99), checked, misses);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const int updates = argc > 1 ? std::max(10, std::atoi(argv[1])) : 2000;
  auto nurbs = [](unidist::NurbsSurface s) {
    return std::make_shared<unidist::NurbsModel>(std::vector<unidist::NurbsSurface>{std::move(s)}, true);
  };
  const std::vector<Family> families = {
      {"nurbs-nurbs", nurbs(nurbs_fixtures::sphereSurface(kBall)), nurbs(nurbs_fixtures::torusSurface(kR, kTube))},
      {"nurbs-mesh", nurbs(nurbs_fixtures::sphereSurface(kBall)), mesh(meshfix::torus(kR, kTube, 100, 100))},
      {"mesh-mesh", mesh(meshfix::icosphere(kBall, 5)), mesh(meshfix::torus(kR, kTube, 100, 100))},
  };
  std::printf("family,mode,triangles_a,triangles_b,updates,median_us,p99_us,max_us,local_p99_us,local_max_us,first_us,"
              "global_passes,local_steps_per_update,cold_samples,cold_median_us,cold_p99_us,checked,misses\n");
  for (const Family& f : families)
    for (auto mode : {unidist::GlobalPassMode::Background, unidist::GlobalPassMode::Inline}) run(f, mode, updates);
}
