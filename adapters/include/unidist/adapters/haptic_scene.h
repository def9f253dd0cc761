// Haptic scene files for `unidist haptic` (format in docs/tracking.md): probes moved along smooth paths through
// waypoints against static environment models, sampled at a servo rate, with the tracker's options.
//
//   {"servo_rate_hz": 1000, "steps": 1200,
//    "tracker": {"cutoff": 10, "stiffness": 0.5, "damping": 0, "global_period": 100, "global_pass": "inline"},
//    "environment": [{"name": "patch", "model": "wavy.unurbs.json", "pose": [tx,ty,tz,qw,qx,qy,qz]}],
//    "probes": [{"name": "ball", "model": "ball.unurbs.json", "waypoints": [[tx,ty,tz,qw,qx,qy,qz], ...]}]}
//
// Model texts are primitive specs or files (relative paths from the scene's folder), as in sim scenes; probes
// and environment models naming the same text share one loaded model. Every problem throws InputError naming
// the scene file and the key.
#pragma once

#include "unidist/model.h"
#include "unidist/tracker.h"

#include <memory>
#include <string>
#include <vector>

namespace unidist::haptic {

struct EnvironmentModel {
  std::string name;
  std::shared_ptr<const Model> model;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< fixed for the whole replay
};

struct Probe {
  std::string name;
  std::shared_ptr<const Model> model;
  std::vector<Eigen::Isometry3d> waypoints;  ///< at least two; the path passes through each
};

struct HapticScene {
  std::string path;          ///< the file read (for messages)
  double servoRateHz = 1000;  ///< updates per second: the tracker's timeStep is its inverse
  int steps = 1000;          ///< updates along the whole path (>= 2)
  TrackerOptions tracker;    ///< cutoff, stiffness, damping, penaltyDistance, guard, globalPeriod, globalPass
  /// A stateless global minimum counts as missed when it is below the tracker's deepest minimum by more than
  /// this; < 0 → 1e-3 × cutoff.
  double missTolerance = -1;
  std::vector<EnvironmentModel> environment;
  std::vector<Probe> probes;
};

HapticScene loadHapticScene(const std::string& path);
/// The same from text; `baseDir` resolves relative model paths, `what` names the source in messages.
HapticScene parseHapticScene(const std::string& jsonText, const std::string& baseDir, const std::string& what);

}  // namespace unidist::haptic
