// Scene files for `unidist sim` and the engine plugins' scene runners: one JSON description shared by Bullet
// and ODE (format in docs/scenes.md), and the engine-neutral result of running one.
//
//   {"gravity": [0,0,-9.81], "dt": 0.004, "steps": 1000,
//    "bodies": [{"name": "floor", "model": "plane:nx=0,ny=0,nz=1,d=0", "static": true},
//               {"name": "ball", "model": "ball.unurbs.json", "pose": [tx,ty,tz,qw,qx,qy,qz],
//                "mass": 1.0, "friction": 0.5, "restitution": 0.0}]}
//
// A body's model is a primitive spec or a model file (relative paths are relative to the scene file); bodies
// naming the same model share one loaded model (one hierarchy). Unknown keys, missing required keys, wrong
// types, duplicate names and bad values throw InputError naming the scene file and the body.
#pragma once

#include "unidist/model.h"
#include "unidist/types.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace unidist {

struct SceneBody {
  std::string name;
  std::string modelSource;                 ///< the "model" text as written
  std::shared_ptr<const Model> model;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< model frame in the world, at step 0
  bool isStatic = false;
  double mass = 0;         ///< > 0 for dynamic bodies; 0 for static ones
  double friction = 0.5;   ///< Coulomb coefficient, >= 0
  double restitution = 0;  ///< in [0, 1]
  double tolerance = -1;   ///< absolute query accuracy for this body's contacts; < 0: the engine's default
  Eigen::Vector3d linearVelocity = Eigen::Vector3d::Zero();   ///< initial, world frame
  Eigen::Vector3d angularVelocity = Eigen::Vector3d::Zero();  ///< initial, world frame
};

struct Scene {
  std::string path;  ///< the file read (for messages)
  Eigen::Vector3d gravity = Eigen::Vector3d(0, 0, -9.81);
  double dt = 1.0 / 240;  ///< fixed step, > 0
  int steps = 1000;       ///< >= 0
  std::vector<SceneBody> bodies;
};

/// Reads and validates a scene file.
Scene loadScene(const std::string& path);
/// The same from text; `baseDir` resolves relative model paths, `what` names the source in messages.
Scene parseScene(const std::string& jsonText, const std::string& baseDir, const std::string& what);

/// One body after a run.
struct BodyState {
  std::string name;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< model frame in the world
  Eigen::Vector3d linearVelocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d angularVelocity = Eigen::Vector3d::Zero();
};

/// What a scene runner reports (the `unidist sim --json` object).
struct SimResult {
  std::string engine;                ///< "bullet" or "ode"
  int steps = 0;
  std::vector<BodyState> bodies;     ///< in scene order, static bodies included
  double maxPenetration = 0;         ///< deepest contact penetration seen over the run (>= 0, model length)
  int contacts = 0;                  ///< contact points in the last step
  double stepsPerSecond = 0;         ///< wall clock, collision + solver
};

/// A contact point the engine was handed in one step (for pictures): the world point (midway between the two
/// surfaces), the engine's unit normal and the separation (<= 0: touching or penetrating).
struct SimContact {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double separation = 0;
};

/// Options of a run, shared by both engines' runners.
struct SimOptions {
  int steps = -1;  ///< < 0: the scene's
  /// Called after every `recordEvery`-th step (and after the last) with the step number and the bodies'
  /// states; null: nothing recorded. Used for trajectory CSVs.
  int recordEvery = 0;
  std::function<void(int step, const std::vector<BodyState>& bodies)> record;
  /// Called before the first step (step 0, no contacts), after every `frameEvery`-th step and after the last,
  /// with the bodies' states and that step's touching contacts; null: nothing collected. Used for pictures.
  int frameEvery = 0;
  std::function<void(int step, const std::vector<BodyState>& bodies, const std::vector<SimContact>& contacts)> frame;
};

}  // namespace unidist
