// Watches a simulated trajectory step by step against stated bounds: finite states, every dynamic body above the
// scene's static half-spaces (no tunnelling through the ground), stacked bodies in their order (no tunnelling
// through each other), no energy gain (kinetic + potential) after settling, and a fingerprint of every step for a
// bitwise comparison with a rerun. Used by the long-run program (docs/reliability.md, "Long runs").
#pragma once

#include "unidist/adapters/scene.h"

#include <cstdint>
#include <string>
#include <vector>

namespace longrun {

/// The stated bounds, relative to the scene so that millimetre and metre scenes get the same checks.
struct Bounds {
  /// A body may sink this fraction of its own bounding-box diagonal into a ground half-space.
  double groundAllowance = 0.01;
  /// The deepest contact the engine is handed may be this fraction of the smallest dynamic body's diagonal.
  double penetrationAllowance = 0.01;
  /// After `settleStep`, E(t) may exceed E(settleStep) by at most this fraction of sum(m |g| diagonal) over the
  /// dynamic bodies (the energy of lifting each body by that fraction of its size); before it, E(t) may exceed
  /// E(0) by the same amount. (Bullet's position correction re-injects energy into a ball rocking in its pocket:
  /// 1.4e-4 of this sum was measured within 30 s.)
  double energyAllowance = 1e-3;
  int settleStep = 2400;
};

/// A pair of dynamic bodies stacked at the start (footprints overlap, the upper's centre above the lower's top).
struct StackedPair {
  std::size_t lower = 0, upper = 0;
};

class TrajectoryMonitor {
 public:
  TrajectoryMonitor(const unidist::Scene& scene, const Bounds& bounds, int steps);

  /// Checks one step's states (scene order, static bodies included). Step 0 is the scene's initial state.
  void observe(int step, const std::vector<unidist::BodyState>& bodies);

  const std::vector<StackedPair>& stackedPairs() const { return stacked_; }
  const std::vector<std::uint64_t>& fingerprints() const { return fingerprints_; }

  // What was seen (valid after the last observe()).
  int firstNonFiniteStep = -1;                ///< -1: none
  std::vector<double> minGroundClearance;     ///< per body (scene order; +inf for static bodies or no ground)
  std::vector<double> groundAllowance;        ///< per body, model length (negative clearance allowed down to -this)
  std::vector<double> maxDriftAfterSettling;  ///< per body: largest sideways (across `up`) move from its settled place
  double minStackGap = 0;                     ///< min over pairs and steps of (upper lowest - lower lowest) height
  int stackViolationStep = -1;                ///< first step where a stacked pair lost its order
  double initialEnergy = 0, settledEnergy = 0;
  double maxExcessOverInitial = 0;            ///< max over steps of E(t) - E(0)
  double maxExcessAfterSettling = 0;          ///< max over steps >= settleStep of E(t) - E(settleStep)
  double energyBound = 0;                     ///< the allowance in energy units
  int energyViolationStep = -1;

  /// One line per violated bound (empty: all held).
  std::vector<std::string> violations() const;

 private:
  struct DynamicBody {
    std::size_t index;
    double mass;
    Eigen::Isometry3d X_MB;  // principal body frame in the model frame
    Eigen::Vector3d moments;
  };
  double energy(const std::vector<unidist::BodyState>& bodies) const;
  /// Lowest point of body i along `up` (exact: the model's support map).
  double lowest(std::size_t i, const Eigen::Isometry3d& X_WM, const Eigen::Vector3d& up) const;

  const unidist::Scene& scene_;
  Bounds bounds_;
  Eigen::Vector3d up_;
  std::vector<DynamicBody> dynamic_;
  std::vector<std::pair<Eigen::Vector3d, double>> grounds_;  // world half-spaces n·x <= d
  std::vector<StackedPair> stacked_;
  std::vector<std::uint64_t> fingerprints_;
  std::vector<Eigen::Vector3d> settledPlaces_;
};

}  // namespace longrun
