// Replays a haptic scene: one unidist::Tracker per probe–environment pair, every update timed, and after it
// (outside the timing) the stateless query at the same poses, to count the updates where the tracker missed the
// global minimum within the cutoff.
#pragma once

#include "unidist/adapters/haptic_scene.h"

#include <Eigen/Core>

#include <limits>
#include <string>
#include <vector>

namespace unidist::haptic {

struct PairReplay {
  std::string probe, environment;
  std::size_t probeIndex = 0;
  std::vector<Eigen::Vector3d> force;  ///< on the probe, world, one per step
  std::vector<double> updateUs;        ///< tracker.update() wall time per step; [0] ran the first global pass
  std::vector<double> statelessUs;     ///< the stateless query's time, for the steps it ran (not culled)
  int minimaMax = 0;                   ///< most minima reported by one update
  int checked = 0;                     ///< steps where the stateless query had a minimum within the cutoff
  int misses = 0;                      ///< updates that missed the global minimum (haptic_scene.h, missTolerance)
  int belowStateless = 0;              ///< updates whose deepest minimum is below the stateless one (phantoms)
  double maxForceJump = 0;             ///< largest |F(t) − F(t − 1)|
  double deepest = std::numeric_limits<double>::infinity();  ///< smallest distance the tracker reported
  long globalPasses = 0;
  double cutoff = 0, tolerance = 0;    ///< resolved by the tracker
};

struct Replay {
  double timeStep = 0;  ///< seconds between updates
  double missTolerance = 0;
  int steps = 0;
  std::vector<PairReplay> pairs;  ///< probe-major: probe 0 against every environment model, then probe 1, ...
};

Replay replay(const HapticScene& scene);

/// The p-quantile (0..1) of v, nearest rank; 0 for an empty v.
double quantile(std::vector<double> v, double p);

}  // namespace unidist::haptic
