// `unidist haptic` as a black box: the default scene's --json (every key, finite, the tracker tracked something,
// few global misses, a bounded force jump), --plot writing PNG files, and bad scenes (exit 2, nothing on stdout,
// one stderr line naming the key).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "run_unidist.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace {

using nlohmann::json;
using unidist::testing::Outcome;
using unidist::testing::run;
namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("unidist_haptic_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

// The default scene once, with plots: the replay takes ~10 s (the stateless check at every update dominates).
TEST(CliHaptic, DefaultSceneJsonAndPlots) {
  const Outcome r = run({"haptic", "--json", "--plot", scratch("plots").string()});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  const json j = json::parse(r.out);
  const std::vector<std::string> keys = {"updates", "median_update_us", "p99_update_us", "max_force_jump",
                                         "minima_tracked_max", "global_misses"};
  EXPECT_EQ(j.size(), keys.size()) << r.out;
  for (const std::string& k : keys) {
    ASSERT_TRUE(j.contains(k) && j[k].is_number()) << k << " in " << r.out;
    EXPECT_TRUE(std::isfinite(j[k].get<double>())) << k;
  }
  EXPECT_EQ(j["updates"].get<long>(), 4 * 1200);  // 2 probes x 2 environment models x 1200 steps
  EXPECT_GE(j["minima_tracked_max"].get<int>(), 1);
  EXPECT_GT(j["median_update_us"].get<double>(), 0);
  // Minima are born on the faceted bumpy mesh between global passes (tracker.h: "Discrete models gain minima by
  // birth"); the next pass finds them. Measured: 37 of 4800 updates, nearly all the NURBS ball on the mesh.
  EXPECT_LE(j["global_misses"].get<int>(), 80);
  // Minima pushing the same way share one spring and a jump between branches is not damped (tracker.h, "Forces"):
  // measured 1.69 against a contact force of about 5 (12.3 when each facet minimum pushed with the full spring
  // and a jump's distance change was damped as a speed).
  EXPECT_LT(j["max_force_jump"].get<double>(), 3);

  // One per probe-environment pair and one total per probe.
  for (const char* name : {"force_nurbs_ball_nurbs_hill.png", "force_nurbs_ball_bumpy_mesh.png",
                           "force_mesh_tool_nurbs_hill.png", "force_mesh_tool_bumpy_mesh.png",
                           "force_nurbs_ball_total.png", "force_mesh_tool_total.png"}) {
    std::ifstream png(scratch("plots") / name, std::ios::binary);
    ASSERT_TRUE(png) << name;
    char signature[8] = {};
    png.read(signature, 8);
    EXPECT_EQ(std::string(signature, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << name;
  }
}

// A guard twice the cutoff keeps minima alive between the cutoff and cutoff + 2·guard, where a local walk over the
// bumpy slab could end on its bottom face and read the slab's thickness as a depth (deepest −322.8, |F| 2,270,
// the tracker below the stateless minimum at 315 updates). Penetrating minima are now checked against the
// models' inside tests.
TEST(CliHaptic, AWideGuardReportsNoFalseOverlap) {
  json s = json::parse(std::ifstream(std::string(UNIDIST_SCENES_DIR) + "/haptic.json"));
  s["tracker"]["guard"] = 20;
  s["probes"] = json::array({s["probes"][0]});            // the NURBS ball
  s["environment"] = json::array({s["environment"][1]});  // the bumpy mesh slab
  for (json* models : {&s["probes"], &s["environment"]})
    for (json& m : *models) m["model"] = std::string(UNIDIST_SCENES_DIR) + "/" + m["model"].get<std::string>();
  const fs::path path = scratch("wide_guard.json");
  std::ofstream(path) << s.dump();
  const Outcome r = run({"haptic", "--scene", path.string()});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("below it 0;"), std::string::npos) << r.out;
}

/// Runs a scene text and expects one error line containing `expected`, exit 2 and nothing on stdout.
void expectBadScene(const std::string& text, const std::string& expected) {
  const fs::path path = scratch("bad.json");
  std::ofstream(path) << text;
  const Outcome r = run({"haptic", "--scene", path.string(), "--json"});
  EXPECT_EQ(r.exitCode, 2) << text;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_EQ(r.err.rfind("unidist: error: ", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(expected), std::string::npos) << "expected '" << expected << "' in: " << r.err;
}

std::string scene(const std::string& tracker, const std::string& envModel, const std::string& waypoint) {
  return R"({"steps": 10, "tracker": )" + tracker + R"(, "environment": [{"name": "floor", "model": ")" + envModel +
         R"("}], "probes": [{"name": "ball", "model": "sphere:r=1", "waypoints": [[0, 0, 2, 1, 0, 0, 0], )" +
         waypoint + "]}]}";
}

TEST(CliHaptic, BadScenes) {
  const std::string tracker = R"({"cutoff": 0.1, "stiffness": 10})";
  const std::string env = "box:hx=5,hy=5,hz=1";
  const std::string waypoint = "[1, 0, 1.05, 1, 0, 0, 0]";
  // The good scene runs (so each failure below is the one change).
  std::ofstream(scratch("good.json")) << scene(tracker, env, waypoint);
  const Outcome good = run({"haptic", "--scene", scratch("good.json").string(), "--json"});
  EXPECT_EQ(good.exitCode, 0) << good.err;

  expectBadScene(R"({"tracker": {"cutoff": 0.1, "stiffness": 1}, "environment": [], "probes": []})",
                 "missing key \"steps\"");
  expectBadScene(scene(R"({"cutoff": 0.1})", env, waypoint), "tracker: missing key \"stiffness\"");
  expectBadScene(scene(R"({"cutoff": 0.1, "stiffness": -1})", env, waypoint), "tracker.stiffness: must be >= 0");
  expectBadScene(scene(tracker, "no_such_model.obj", waypoint), "environment[0] (\"floor\").model");
  expectBadScene(scene(tracker, env, "[1, 0, NaN, 1, 0, 0, 0]"), "not valid JSON");  // JSON has no NaN
  expectBadScene(scene(tracker, env, "[1, 0, 1e999, 1, 0, 0, 0]"), "number overflow");
  expectBadScene(scene(tracker, env, R"([1, 0, "nan", 1, 0, 0, 0])"), "probes[0] (\"ball\").waypoints[1][2]: must be a number");
  expectBadScene(scene(R"({"cutoff": 0.1, "stiffness": 1, "global_pass": "sometimes"})", env, waypoint),
                 "tracker.global_pass");
  const Outcome missing = run({"haptic", "--scene", scratch("absent.json").string()});
  EXPECT_EQ(missing.exitCode, 2);
  EXPECT_TRUE(missing.out.empty());
}

}  // namespace
