// `unidist haptic [--scene S] [--json] [--plot DIR]`: replays a haptic scene (docs/tracking.md) — probes moved
// along smooth paths into and out of contact with environment models, one unidist::Tracker per pair — and
// reports the update rate, the minima tracked, the force's continuity and the updates where the tracker missed
// the stateless global minimum. --json prints one object:
//   {"updates": n, "median_update_us": m, "p99_update_us": p, "max_force_jump": j, "minima_tracked_max": k,
//    "global_misses": g}
// --plot DIR writes force-vs-time PNGs: one per probe–environment pair and one per probe's total.
#include "commands.h"
#include "output.h"

#include "haptic_replay.h"
#include "unidist/adapters/haptic_scene.h"
#ifdef UNIDIST_HAVE_PNG
#include "force_plot.h"
#endif

#include "unidist/types.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <system_error>

#ifndef UNIDIST_SCENES_DIR
#error "UNIDIST_SCENES_DIR must name demos/scenes (the default haptic scene)"
#endif

namespace unidist::cli {
namespace {

using haptic::PairReplay;
using haptic::quantile;
using haptic::Replay;

/// Every update's time except each tracker's first (its synchronous global pass: not a servo update).
std::vector<double> servoTimes(const std::vector<PairReplay>& pairs) {
  std::vector<double> us;
  for (const PairReplay& p : pairs) us.insert(us.end(), p.updateUs.begin() + (p.updateUs.empty() ? 0 : 1), p.updateUs.end());
  return us;
}

std::string fixed(double v, int digits) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

/// A readable number: 4 significant digits.
std::string brief(double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

struct Totals {
  long updates = 0;
  int minimaMax = 0, misses = 0, checked = 0;
  double maxForceJump = 0;
};

Totals totalsOf(const Replay& r) {
  Totals t;
  for (const PairReplay& p : r.pairs) {
    t.updates += static_cast<long>(p.updateUs.size());
    t.minimaMax = std::max(t.minimaMax, p.minimaMax);
    t.misses += p.misses;
    t.checked += p.checked;
    t.maxForceJump = std::max(t.maxForceJump, p.maxForceJump);
  }
  return t;
}

std::string asJson(const Replay& r) {
  const Totals t = totalsOf(r);
  const std::vector<double> us = servoTimes(r.pairs);
  return "{\"updates\": " + std::to_string(t.updates) + ", \"median_update_us\": " + jsonNumber(quantile(us, 0.5)) +
         ", \"p99_update_us\": " + jsonNumber(quantile(us, 0.99)) + ", \"max_force_jump\": " +
         jsonNumber(t.maxForceJump) + ", \"minima_tracked_max\": " + std::to_string(t.minimaMax) +
         ", \"global_misses\": " + std::to_string(t.misses) + "}\n";
}

std::string asText(const haptic::HapticScene& scene, const Replay& r) {
  const Totals t = totalsOf(r);
  const std::vector<double> us = servoTimes(r.pairs);
  const TrackerOptions& o = scene.tracker;
  std::string out = "haptic scene " + scene.path + ": " + std::to_string(scene.probes.size()) + " probe(s) x " +
                    std::to_string(scene.environment.size()) + " environment model(s), " +
                    std::to_string(r.steps) + " steps at " + brief(scene.servoRateHz) + " Hz (" +
                    brief(r.steps * r.timeStep) + " s), cutoff " + brief(o.cutoff) + ", stiffness " +
                    brief(o.stiffness) + ", damping " + brief(o.damping) + ", global pass " +
                    (o.globalPass == GlobalPassMode::Inline ? "inline" : "background") + " at least every " +
                    std::to_string(o.globalPeriod) + " updates\n";
  out += "updates " + std::to_string(t.updates) + ": median " + fixed(quantile(us, 0.5), 1) + " us, p99 " +
         fixed(quantile(us, 0.99), 1) + " us, max " + fixed(us.empty() ? 0 : *std::max_element(us.begin(), us.end()), 1) +
         " us (each pair's first update, its synchronous global pass, not counted)\n";
  out += "minima tracked at most " + std::to_string(t.minimaMax) + " per pair; largest force change per update " +
         brief(t.maxForceJump) + "; global minima missed " + std::to_string(t.misses) + " of " +
         std::to_string(t.checked) + " updates with one within the cutoff (tolerance " + brief(r.missTolerance) + ")\n";
  for (const PairReplay& p : r.pairs) {
    double maxForce = 0;
    for (const Eigen::Vector3d& f : p.force) maxForce = std::max(maxForce, f.norm());
    std::vector<double> own(p.updateUs.begin() + (p.updateUs.empty() ? 0 : 1), p.updateUs.end());
    out += "  " + p.probe + " / " + p.environment + ": update median " + fixed(quantile(own, 0.5), 1) + " us, p99 " +
           fixed(quantile(own, 0.99), 1) + " us; " + std::to_string(p.globalPasses) + " global passes; minima <= " +
           std::to_string(p.minimaMax) + "; deepest " + (p.deepest < 1e300 ? brief(p.deepest) : "none") +
           "; max |F| " + brief(maxForce) + ", max change " + brief(p.maxForceJump) + "; misses " +
           std::to_string(p.misses) + " of " + std::to_string(p.checked) + ", below it " +
           std::to_string(p.belowStateless) + "; stateless query median " +
           fixed(quantile(p.statelessUs, 0.5), 1) + " us over " + std::to_string(p.statelessUs.size()) + " steps\n";
  }
  return out;
}

/// A name usable in a file name: letters, digits, '-' and '_' kept, anything else '_'.
std::string fileSafe(const std::string& name) {
  std::string s = name;
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
  return s;
}

/// Writes the plots; returns how many.
int writePlots([[maybe_unused]] const std::string& dir, [[maybe_unused]] const haptic::HapticScene& scene,
               [[maybe_unused]] const Replay& r) {
  int written = 0;
#ifdef UNIDIST_HAVE_PNG
  const auto file = [&](const std::string& name) { return (std::filesystem::path(dir) / name).string(); };
  for (std::size_t i = 0; i < scene.probes.size(); ++i) {
    std::vector<Eigen::Vector3d> total(static_cast<std::size_t>(r.steps), Eigen::Vector3d::Zero());
    for (const PairReplay& p : r.pairs) {
      if (p.probeIndex != i) continue;
      haptic::writeForcePlot(file("force_" + fileSafe(p.probe) + "_" + fileSafe(p.environment) + ".png"),
                             "force on " + p.probe + " from " + p.environment, p.force, r.timeStep);
      for (std::size_t k = 0; k < p.force.size(); ++k) total[k] += p.force[k];
      ++written;
    }
    const std::string& name = scene.probes[i].name;
    haptic::writeForcePlot(file("force_" + fileSafe(name) + "_total.png"), "total force on " + name, total,
                           r.timeStep);
    ++written;
  }
#endif
  return written;
}

}  // namespace

std::string runHaptic(const HapticArgs& args) {
  if (args.hasScene && args.scene.empty()) throw InputError("--scene needs a file (got '')");
  if (args.hasPlot) {
#ifndef UNIDIST_HAVE_PNG
    throw InputError("--plot: this unidist was built without libpng; install libpng-dev and rebuild");
#endif
    if (args.plot.empty()) throw InputError("--plot needs a directory (got '')");
    std::error_code ec;
    std::filesystem::create_directories(args.plot, ec);
    if (ec || !std::filesystem::is_directory(args.plot))
      throw InputError("--plot: cannot create the directory " + args.plot + (ec ? " (" + ec.message() + ")" : ""));
  }
  const haptic::HapticScene scene =
      haptic::loadHapticScene(args.hasScene ? args.scene : std::string(UNIDIST_SCENES_DIR) + "/haptic.json");
  const Replay r = haptic::replay(scene);
  const int plots = args.hasPlot ? writePlots(args.plot, scene, r) : 0;
  if (args.json) return asJson(r);
  std::string out = asText(scene, r);
  if (args.hasPlot) out += "plots: " + std::to_string(plots) + " PNG files (force vs time) in " + args.plot + "\n";
  return out;
}

}  // namespace unidist::cli
