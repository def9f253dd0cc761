#include "haptic_replay.h"

#include "probe_path.h"

#include "unidist/contacts.h"
#include "unidist/distance.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

namespace unidist::haptic {
namespace {

double microsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
}

/// True when the pair is proved farther apart than `cutoff`: no minimum within it, no stateless query needed.
bool provablyBeyond(const Model& a, const Eigen::Isometry3d& X_WA, const Model& b, const Eigen::Isometry3d& X_WB,
                    double cutoff) {
  if (!a.localBounds().bounded() || !b.localBounds().bounded()) return false;
  const BoundingSphere sa = a.localBoundingSphere(), sb = b.localBoundingSphere();
  if ((X_WA * sa.center - X_WB * sb.center).norm() - sa.radius - sb.radius > cutoff) return true;
  // The overlap test of A grown by the cutoff proves "apart" far more cheaply than contacts() measures it.
  DistanceOptions o;
  o.compute = Compute::Overlap;
  o.inflateA = cutoff;
  return distance(a, X_WA, b, X_WB, o).lowerBound > 0;
}

/// The stateless global minimum within the cutoff (inf: none), as the tracker's own global pass would see it.
double statelessMinimum(const Model& probe, const Eigen::Isometry3d& X_WP, const EnvironmentModel& env,
                        const TrackerOptions& resolved) {
  ContactOptions co;
  co.margin = resolved.cutoff;
  co.tolerance = resolved.tolerance;
  co.maxContacts = 1;  // deepest first: only the global minimum is compared
  const std::vector<Contact> cs = contacts(probe, X_WP, *env.model, env.pose, co);
  return cs.empty() ? std::numeric_limits<double>::infinity() : cs.front().distance;
}

}  // namespace

double quantile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const auto rank = static_cast<std::size_t>(std::ceil(p * static_cast<double>(v.size())));
  return v[std::min(v.size() - 1, rank > 0 ? rank - 1 : 0)];
}

Replay replay(const HapticScene& scene) {
  Replay r;
  r.timeStep = scene.tracker.timeStep;
  r.steps = scene.steps;
  r.missTolerance = scene.missTolerance >= 0 ? scene.missTolerance : 1e-3 * scene.tracker.cutoff;
  std::vector<std::vector<Eigen::Isometry3d>> paths;
  for (const Probe& p : scene.probes) paths.push_back(samplePath(p.waypoints, scene.steps));
  std::vector<std::unique_ptr<Tracker>> trackers;
  for (std::size_t i = 0; i < scene.probes.size(); ++i)
    for (const EnvironmentModel& e : scene.environment) {
      trackers.push_back(std::make_unique<Tracker>(scene.probes[i].model, e.model, scene.tracker));
      PairReplay pr;
      pr.probe = scene.probes[i].name;
      pr.environment = e.name;
      pr.probeIndex = i;
      pr.cutoff = trackers.back()->options().cutoff;
      pr.tolerance = trackers.back()->options().tolerance;
      r.pairs.push_back(std::move(pr));
    }
  const std::size_t envs = scene.environment.size();
  for (std::size_t step = 0; step < static_cast<std::size_t>(scene.steps); ++step)
    for (std::size_t k = 0; k < trackers.size(); ++k) {
      PairReplay& pr = r.pairs[k];
      const Model& probe = *scene.probes[pr.probeIndex].model;
      const EnvironmentModel& env = scene.environment[k % envs];
      const Eigen::Isometry3d& X_WP = paths[pr.probeIndex][step];

      const auto t0 = std::chrono::steady_clock::now();
      const TrackerUpdate& u = trackers[k]->update(X_WP, env.pose);
      pr.updateUs.push_back(microsSince(t0));

      if (!pr.force.empty()) pr.maxForceJump = std::max(pr.maxForceJump, (u.force - pr.force.back()).norm());
      pr.force.push_back(u.force);
      pr.minimaMax = std::max(pr.minimaMax, u.minima);
      pr.deepest = std::min(pr.deepest, u.deepest);
      if (provablyBeyond(probe, X_WP, *env.model, env.pose, pr.cutoff)) continue;
      const auto t1 = std::chrono::steady_clock::now();
      const double global = statelessMinimum(probe, X_WP, env, trackers[k]->options());
      pr.statelessUs.push_back(microsSince(t1));
      // A minimum right at the cutoff may be reported by one side only: not a miss.
      // The other way round: a reported minimum below every real one (a phantom).
      pr.belowStateless += u.deepest < std::min(global, pr.cutoff) - r.missTolerance ? 1 : 0;
      if (global > pr.cutoff - r.missTolerance) continue;
      ++pr.checked;
      pr.misses += (u.minima == 0 || global < u.deepest - r.missTolerance) ? 1 : 0;
    }
  for (std::size_t k = 0; k < trackers.size(); ++k) {
    trackers[k]->waitForGlobalPass();
    r.pairs[k].globalPasses = trackers[k]->counters().globalPasses;
  }
  return r;
}

}  // namespace unidist::haptic
