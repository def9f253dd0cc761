// `unidist sim SCENE --engine bullet|ode [--steps N] [--json] [--trajectory FILE] [--record-every K]`: runs a
// scene file (docs/scenes.md) headless in either engine with the unidist plugin and prints the final state.
// --json prints one object:
//   {"engine": "...", "steps": n, "bodies": [{"name": "...", "pose": [tx,ty,tz,qw,qx,qy,qz],
//    "linear_velocity": [..], "angular_velocity": [..]}], "max_penetration": p, "contacts": c,
//    "steps_per_second": s}
// with the models' final world poses; --trajectory writes every K-th step's poses as CSV.
#include "commands.h"
#include "output.h"

#include "unidist/adapters/scene.h"
#include "unidist/adapters/spec.h"
#include "unidist/bullet/scene_runner.h"
#include "unidist/ode/scene_runner.h"

#include <cmath>
#include <fstream>

namespace unidist::cli {
namespace {

std::string jsonPose(const Eigen::Isometry3d& X) {
  const Eigen::Quaterniond q(X.linear());
  const Eigen::Vector3d t = X.translation();
  return "[" + jsonNumber(t.x()) + "," + jsonNumber(t.y()) + "," + jsonNumber(t.z()) + "," + jsonNumber(q.w()) +
         "," + jsonNumber(q.x()) + "," + jsonNumber(q.y()) + "," + jsonNumber(q.z()) + "]";
}

std::string asJson(const SimResult& r) {
  std::string out = "{\"engine\": " + jsonString(r.engine) + ", \"steps\": " + std::to_string(r.steps) +
                    ", \"bodies\": [";
  for (std::size_t i = 0; i < r.bodies.size(); ++i) {
    const BodyState& b = r.bodies[i];
    out += std::string(i ? ", " : "") + "{\"name\": " + jsonString(b.name) + ", \"pose\": " + jsonPose(b.pose) +
           ", \"linear_velocity\": " + jsonVector(b.linearVelocity) +
           ", \"angular_velocity\": " + jsonVector(b.angularVelocity) + "}";
  }
  out += "], \"max_penetration\": " + jsonNumber(r.maxPenetration) + ", \"contacts\": " + std::to_string(r.contacts) +
         ", \"steps_per_second\": " + jsonNumber(r.stepsPerSecond) + "}\n";
  return out;
}

std::string asText(const SimResult& r) {
  std::string out = "engine " + r.engine + ", " + std::to_string(r.steps) + " steps, " +
                    textNumber(std::round(r.stepsPerSecond)) + " steps/s, " + std::to_string(r.contacts) +
                    " contacts in the last step, max penetration " + textNumber(r.maxPenetration) + "\n";
  for (const BodyState& b : r.bodies) {
    const Eigen::Quaterniond q(b.pose.linear());
    out += "  " + b.name + ": position " + textVector(b.pose.translation()) + "  quaternion " +
           textNumber(q.w()) + " " + textVector(q.vec()) + "  |v| " + textNumber(b.linearVelocity.norm()) + "\n";
  }
  return out;
}

int wholeNumber(const std::string& text, const char* what, int min) {
  const double n = parseNumber(text, what);
  if (n < min || n != std::floor(n) || n > 1e8)
    throw InputError(std::string(what) + " must be a whole number >= " + std::to_string(min) + " (got " + text + ")");
  return static_cast<int>(n);
}

}  // namespace

std::string runSim(const SimArgs& args) {
  if (args.engine != "bullet" && args.engine != "ode")
    throw InputError("--engine must be 'bullet' or 'ode' (got '" + args.engine + "')");
  SimOptions options;
  if (args.hasSteps) options.steps = wholeNumber(args.steps, "--steps", 0);
  const Scene scene = loadScene(args.scene);

  std::ofstream csv;
  if (!args.trajectory.empty()) {
    csv.open(args.trajectory);
    if (!csv) throw InputError(args.trajectory + ": cannot write the trajectory");
    csv << "step,time,body,tx,ty,tz,qw,qx,qy,qz\n";
    csv.precision(17);
    options.recordEvery = args.hasRecordEvery ? wholeNumber(args.recordEvery, "--record-every", 1) : 10;
    options.record = [&](int step, const std::vector<BodyState>& bodies) {
      for (const BodyState& b : bodies) {
        const Eigen::Quaterniond q(b.pose.linear());
        const Eigen::Vector3d t = b.pose.translation();
        csv << step << ',' << step * scene.dt << ',' << b.name << ',' << t.x() << ',' << t.y() << ',' << t.z() << ','
            << q.w() << ',' << q.x() << ',' << q.y() << ',' << q.z() << '\n';
      }
    };
  }
  const SimResult r = args.engine == "bullet" ? bullet::runScene(scene, options) : ode::runScene(scene, options);
  if (csv.is_open() && !csv.flush()) throw InputError(args.trajectory + ": write error");
  return args.json ? asJson(r) : asText(r);
}

}  // namespace unidist::cli
