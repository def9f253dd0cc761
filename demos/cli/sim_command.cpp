// `unidist sim SCENE --engine bullet|ode [--steps N] [--json] [--trajectory FILE] [--record-every K]
// [--render DIR [--render-every K] [--render-size WxH]]`: runs a scene file (docs/scenes.md) headless in either
// engine with the unidist plugin and prints the final state; --render writes PNG pictures (docs/pictures.md).
// --json prints one object:
//   {"engine": "...", "steps": n, "bodies": [{"name": "...", "pose": [tx,ty,tz,qw,qx,qy,qz],
//    "linear_velocity": [..], "angular_velocity": [..]}], "max_penetration": p, "contacts": c,
//    "steps_per_second": s}
// with the models' final world poses (and "frames": n with --render); --trajectory writes every K-th step's
// poses as CSV.
#include "commands.h"
#include "output.h"

#include "unidist/adapters/scene.h"
#include "unidist/adapters/spec.h"
#include "unidist/bullet/scene_runner.h"
#include "unidist/ode/scene_runner.h"

#ifdef UNIDIST_HAVE_RENDER
#include "sim_frames.h"
#endif

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <utility>

namespace unidist::cli {
namespace {

std::string jsonPose(const Eigen::Isometry3d& X) {
  const Eigen::Quaterniond q(X.linear());
  const Eigen::Vector3d t = X.translation();
  return "[" + jsonNumber(t.x()) + "," + jsonNumber(t.y()) + "," + jsonNumber(t.z()) + "," + jsonNumber(q.w()) +
         "," + jsonNumber(q.x()) + "," + jsonNumber(q.y()) + "," + jsonNumber(q.z()) + "]";
}

/// What --render wrote, for the report.
struct FramesReport {
  std::string dir;
  int count = 0, width = 0, height = 0;
  double msPerFrame = 0;
};

std::string asJson(const SimResult& r, const FramesReport& frames) {
  std::string out = "{\"engine\": " + jsonString(r.engine) + ", \"steps\": " + std::to_string(r.steps) +
                    ", \"bodies\": [";
  for (std::size_t i = 0; i < r.bodies.size(); ++i) {
    const BodyState& b = r.bodies[i];
    out += std::string(i ? ", " : "") + "{\"name\": " + jsonString(b.name) + ", \"pose\": " + jsonPose(b.pose) +
           ", \"linear_velocity\": " + jsonVector(b.linearVelocity) +
           ", \"angular_velocity\": " + jsonVector(b.angularVelocity) + "}";
  }
  out += "], \"max_penetration\": " + jsonNumber(r.maxPenetration) + ", \"contacts\": " + std::to_string(r.contacts) +
         ", \"steps_per_second\": " + jsonNumber(r.stepsPerSecond);
  if (!frames.dir.empty()) out += ", \"frames\": " + std::to_string(frames.count);
  return out + "}\n";
}

std::string asText(const SimResult& r, const FramesReport& frames) {
  std::string out = "engine " + r.engine + ", " + std::to_string(r.steps) + " steps, " +
                    textNumber(std::round(r.stepsPerSecond)) + " steps/s, " + std::to_string(r.contacts) +
                    " contacts in the last step, max penetration " + textNumber(r.maxPenetration) + "\n";
  for (const BodyState& b : r.bodies) {
    const Eigen::Quaterniond q(b.pose.linear());
    out += "  " + b.name + ": position " + textVector(b.pose.translation()) + "  quaternion " +
           textNumber(q.w()) + " " + textVector(q.vec()) + "  |v| " + textNumber(b.linearVelocity.norm()) + "\n";
  }
  if (!frames.dir.empty()) {
    char ms[32];
    std::snprintf(ms, sizeof ms, "%.1f", frames.msPerFrame);
    out += "frames: " + std::to_string(frames.count) + " PNG pictures of " + std::to_string(frames.width) + " x " +
           std::to_string(frames.height) + " in " + frames.dir + " (frame_00000.png ...), " + ms + " ms each\n";
  }
  return out;
}

int wholeNumber(const std::string& text, const char* what, int min) {
  const double n = parseNumber(text, what);
  if (n < min || n != std::floor(n) || n > 1e8)
    throw InputError(std::string(what) + " must be a whole number >= " + std::to_string(min) + " (got " + text + ")");
  return static_cast<int>(n);
}

/// "WxH" with whole numbers 1..8192 (an OpenGL buffer's limits here).
std::pair<int, int> renderSize(const std::string& text) {
  const std::size_t x = text.find_first_of("xX");
  const auto side = [&](const std::string& part) {
    if (part.empty() || part.find_first_not_of("0123456789") != std::string::npos || part.size() > 5) return -1;
    return std::stoi(part);
  };
  const int w = x == std::string::npos ? -1 : side(text.substr(0, x));
  const int h = x == std::string::npos ? -1 : side(text.substr(x + 1));
  if (w < 1 || h < 1 || w > 8192 || h > 8192)
    throw InputError("--render-size must be WxH, whole numbers of pixels 1..8192 (got '" + text + "')");
  return {w, h};
}

}  // namespace

std::string runSim(const SimArgs& args) {
  if (args.engine != "bullet" && args.engine != "ode")
    throw InputError("--engine must be 'bullet' or 'ode' (got '" + args.engine + "')");
  SimOptions options;
  if (args.hasSteps) options.steps = wholeNumber(args.steps, "--steps", 0);
  if ((args.hasRenderEvery || args.hasRenderSize) && !args.hasRender)
    throw InputError("--render-every and --render-size need --render DIR");
  if (args.hasRender && args.render.empty()) throw InputError("--render needs a directory (got '')");
  [[maybe_unused]] const auto [width, height] = args.hasRenderSize ? renderSize(args.renderSize) : std::pair{640, 480};
  [[maybe_unused]] const int renderEvery = args.hasRenderEvery ? wholeNumber(args.renderEvery, "--render-every", 1) : 0;
#ifndef UNIDIST_HAVE_RENDER
  if (args.hasRender)
    throw InputError("--render: this unidist was built without pictures; install libosmesa6-dev, libqhull-dev and "
                     "libpng-dev and rebuild");
#endif
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
  FramesReport report;
#ifdef UNIDIST_HAVE_RENDER
  std::unique_ptr<SimFrames> frames;
  if (args.hasRender) {
    frames = std::make_unique<SimFrames>(scene, args.render, width, height);
    const int steps = options.steps >= 0 ? options.steps : scene.steps;
    options.frameEvery = renderEvery > 0 ? renderEvery : std::max(1, (steps + 15) / 30);  // about 30 frames
    options.frame = [&](int, const std::vector<BodyState>& bodies, const std::vector<SimContact>& contacts) {
      frames->write(bodies, contacts);
    };
  }
#endif
  const SimResult r = args.engine == "bullet" ? bullet::runScene(scene, options) : ode::runScene(scene, options);
  if (csv.is_open() && !csv.flush()) throw InputError(args.trajectory + ": write error");
#ifdef UNIDIST_HAVE_RENDER
  if (frames)
    report = {args.render, frames->written(), width, height, 1e3 * frames->seconds() / std::max(1, frames->written())};
#endif
  return args.json ? asJson(r, report) : asText(r, report);
}

}  // namespace unidist::cli
