// The `unidist` command as a black box: it is run as a child process (stdout and stderr captured apart) and
// its output is checked against docs/query-contract.md: the JSON fields and their types, the invariant
// point_b − point_a = distance · normal, 17 significant digits, and for every class of bad input exit code 2,
// empty stdout and exactly one stderr line "unidist: error: ...".
#include <Eigen/Core>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "run_unidist.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

namespace {

using nlohmann::json;
using unidist::testing::Outcome;
using unidist::testing::run;

std::string describe(const std::vector<std::string>& args, const Outcome& r) {
  std::string s = "unidist";
  for (const std::string& a : args) s += " '" + a + "'";
  return s + "\n  exit " + std::to_string(r.exitCode) + " signal " + std::to_string(r.signal) + "\n  stdout: " +
         r.out + "\n  stderr: " + r.err;
}

/// Runs a query that must succeed with --json and returns the parsed object (fails the test otherwise).
json queryJson(std::vector<std::string> args, std::string* raw = nullptr) {
  args.push_back("--json");
  const Outcome r = run(args);
  EXPECT_EQ(r.exitCode, 0) << describe(args, r);
  EXPECT_EQ(r.err, "") << describe(args, r);
  // Exactly one line holding one object.
  EXPECT_FALSE(r.out.empty());
  if (!r.out.empty()) {
    EXPECT_EQ(r.out.back(), '\n');
    EXPECT_EQ(r.out.find('\n'), r.out.size() - 1) << r.out;
  }
  if (raw) *raw = r.out;
  try {
    return json::parse(r.out);
  } catch (const std::exception& e) {
    ADD_FAILURE() << "stdout is not JSON: " << e.what() << "\n" << describe(args, r);
    return json::object();
  }
}

Eigen::Vector3d vec(const json& v) { return {v.at(0).get<double>(), v.at(1).get<double>(), v.at(2).get<double>()}; }

// ---------------------------------------------------------------- help and version

TEST(Cli, HelpExitsZero) {
  const std::pair<std::vector<std::string>, const char*> cases[] = {
      {{"--help"}, "distance"}, {{"-h"}, "info"}, {{"distance", "--help"}, "--pose-a"}, {{"info", "--help"}, "info"}};
  for (const auto& [args, word] : cases) {
    const Outcome r = run(args);
    EXPECT_EQ(r.exitCode, 0) << describe(args, r);
    EXPECT_EQ(r.err, "") << describe(args, r);
    EXPECT_NE(r.out.find(word), std::string::npos) << describe(args, r);
  }
  const Outcome d = run({"distance", "--help"});
  for (const char* opt : {"--pose-a", "--pose-b", "--tol", "--rel-tol", "--max-iterations", "--detail-a", "--detail-b",
                          "--compute", "--inflate-a", "--inflate-b", "--json"})
    EXPECT_NE(d.out.find(opt), std::string::npos) << opt;
  const Outcome c = run({"contacts", "--help"});
  for (const char* opt : {"--margin", "--tol", "--rel-tol", "--max-iterations", "--detail-a", "--detail-b"})
    EXPECT_NE(c.out.find(opt), std::string::npos) << opt;
}

TEST(Cli, VersionExitsZero) {
  const Outcome r = run({"--version"});
  EXPECT_EQ(r.exitCode, 0);
  EXPECT_EQ(r.out.rfind("unidist ", 0), 0u) << r.out;
}

// ---------------------------------------------------------------- the JSON answer

TEST(CliDistance, JsonHasEveryFieldWithItsType) {
  const json j = queryJson({"distance", "sphere:r=1", "box:hx=1,hy=1,hz=1", "--pose-a", "3 0 0 1 0 0 0"});
  const char* keys[] = {"distance", "point_a", "point_b", "normal", "lower_bound", "upper_bound",
                        "status", "iterations", "time_us", "build_us"};
  ASSERT_TRUE(j.is_object());
  EXPECT_EQ(j.size(), std::size(keys)) << j.dump();
  for (const char* k : keys) ASSERT_TRUE(j.contains(k)) << k << " missing in " << j.dump();
  EXPECT_TRUE(j["distance"].is_number_float() || j["distance"].is_number());
  for (const char* k : {"point_a", "point_b", "normal"}) {
    ASSERT_TRUE(j[k].is_array() && j[k].size() == 3) << k;
    for (const json& x : j[k]) EXPECT_TRUE(x.is_number()) << k;
  }
  for (const char* k : {"lower_bound", "upper_bound"}) EXPECT_TRUE(j[k].is_number() || j[k].is_null()) << k;
  EXPECT_TRUE(j["status"] == "certified" || j["status"] == "bounded") << j["status"];
  EXPECT_TRUE(j["iterations"].is_number_integer());
  EXPECT_GE(j["iterations"].get<long long>(), 0);
  EXPECT_TRUE(j["time_us"].is_number());
  EXPECT_GE(j["time_us"].get<double>(), 0.0);
  EXPECT_TRUE(j["build_us"].is_number());
  EXPECT_EQ(j["build_us"].get<double>(), 0.0);  // primitives build nothing

  // Sphere centre at x = 3, box face at x = 1: the gap is 1, from A (+x side) toward B: normal -x.
  EXPECT_NEAR(j["distance"].get<double>(), 1.0, 1e-9);
  EXPECT_NEAR((vec(j["normal"]) + Eigen::Vector3d::UnitX()).norm(), 0, 1e-9);
  EXPECT_NEAR((vec(j["point_a"]) - Eigen::Vector3d(2, 0, 0)).norm(), 0, 1e-9);
  EXPECT_NEAR(vec(j["point_b"]).x(), 1.0, 1e-9);
}

struct PairCase {
  const char* name;
  std::vector<std::string> args;
  double truth;  ///< analytic signed distance
};

std::vector<PairCase> pairCases() {
  return {
      {"sphere-sphere separated", {"sphere:r=1", "sphere:r=0.5", "--pose-b", "3 4 0 1 0 0 0"}, 3.5},
      {"sphere-sphere overlapping", {"sphere:r=1", "sphere:r=1", "--pose-b", "0 0 1.5 1 0 0 0"}, -0.5},
      {"sphere-box rotated", {"sphere:r=0.5", "box:hx=1,hy=2,hz=3", "--pose-a", "0 0 5 1 0 0 0", "--pose-b",
                              "0 0 0 0.7071067811865476 0.7071067811865476 0 0"}, 2.5},
      {"ball inside a box", {"sphere:r=1", "box:hx=2,hy=2,hz=2"}, -3.0},
      {"sphere-plane", {"sphere:r=1", "plane:nx=0,ny=0,nz=2,d=0", "--pose-a", "0.3 -7 2.25 1 0 0 0"}, 1.25},
      {"inflated spheres", {"sphere:r=1", "sphere:r=0.5", "--pose-b", "3 4 0 1 0 0 0", "--inflate-a", "0.25",
                            "--inflate-b", "1e-1"}, 3.15},
      {"sphere-capsule with --tol", {"sphere:r=1", "capsule:r=0.5,h=2", "--pose-b", "4 0 1 1 0 0 0", "--tol",
                                     "1e-12"}, 2.5},
  };
}

TEST(CliDistance, PointsNormalAndBoundsAgreeWithTheDistance) {
  for (const PairCase& c : pairCases()) {
    SCOPED_TRACE(c.name);
    std::vector<std::string> args = {"distance"};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const json j = queryJson(args);
    if (!j.contains("distance")) continue;
    const double d = j["distance"].get<double>();
    const Eigen::Vector3d pa = vec(j["point_a"]), pb = vec(j["point_b"]), n = vec(j["normal"]);
    EXPECT_NEAR(d, c.truth, 1e-9);
    EXPECT_NEAR(n.norm(), 1.0, 1e-12);
    EXPECT_NEAR((pb - pa - d * n).norm(), 0.0, 1e-9) << "point_b - point_a != distance * normal";
    if (j["lower_bound"].is_number()) {
      EXPECT_LE(j["lower_bound"].get<double>(), c.truth + 1e-9);
    }
    if (j["upper_bound"].is_number()) {
      EXPECT_GE(j["upper_bound"].get<double>(), c.truth - 1e-9);
    }
  }
}

TEST(CliDistance, SwappingAAndBNegatesTheNormal) {
  const json ab = queryJson({"distance", "sphere:r=1", "box:hx=1,hy=2,hz=3", "--pose-a", "4 0.5 0.25 1 0 0 0"});
  const json ba = queryJson({"distance", "box:hx=1,hy=2,hz=3", "sphere:r=1", "--pose-b", "4 0.5 0.25 1 0 0 0"});
  EXPECT_NEAR(ab["distance"].get<double>(), ba["distance"].get<double>(), 1e-12);
  EXPECT_NEAR((vec(ab["normal"]) + vec(ba["normal"])).norm(), 0, 1e-12);
  EXPECT_NEAR((vec(ab["point_a"]) - vec(ba["point_b"])).norm(), 0, 1e-12);
}

/// Significant digits of a JSON number token ("-1.2300e-5" → 5).
int significantDigits(std::string token) {
  const std::size_t e = token.find_first_of("eE");
  if (e != std::string::npos) token.resize(e);
  std::string digits;
  for (char ch : token)
    if (ch >= '0' && ch <= '9') digits += ch;
  const std::size_t first = digits.find_first_not_of('0');
  return first == std::string::npos ? 1 : static_cast<int>(digits.size() - first);
}

TEST(CliDistance, NumbersHave17SignificantDigits) {
  // 2·√3 − 2: irrational, so the printed value needs all 17 digits (16 if the 17th happens to be 0).
  std::string raw;
  const json j = queryJson({"distance", "sphere:r=1", "sphere:r=1", "--pose-b", "2 2 2 1 0 0 0"}, &raw);
  const std::regex number(R"(-?[0-9][0-9.]*(?:[eE][-+]?[0-9]+)?)");
  const std::regex distanceField(R"("distance": *(-?[0-9][0-9.eE+-]*))");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(raw, m, distanceField)) << raw;
  EXPECT_GE(significantDigits(m[1]), 16) << m[1];
  EXPECT_NEAR(std::strtod(m[1].str().c_str(), nullptr), 2 * std::sqrt(3.0) - 2, 1e-9);
  // Every number token (not "iterations", an integer) is exactly %.17g of its value: nothing rounded away.
  for (auto it = std::sregex_iterator(raw.begin(), raw.end(), number); it != std::sregex_iterator(); ++it) {
    const std::string token = it->str();
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", std::strtod(token.c_str(), nullptr));
    EXPECT_EQ(token, buf) << "in " << raw;
  }
  const double d = j["distance"].get<double>();
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", d);
  EXPECT_EQ(m[1].str(), buf);
}

TEST(CliDistance, HumanReadableReport) {
  const Outcome r = run({"distance", "sphere:r=1", "sphere:r=0.5", "--pose-b", "3 4 0 1 0 0 0"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.err, "");
  for (const char* word : {"distance", "point_a", "point_b", "normal", "bounds", "status"})
    EXPECT_NE(r.out.find(word), std::string::npos) << word << " in\n" << r.out;
  EXPECT_NE(r.out.find("3.5"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find('{'), std::string::npos) << "not JSON without --json";
}

// ---------------------------------------------------------------- the dial: --compute, --rel-tol, --max-iterations,
// --detail-a/-b (unidist/query_options.h). Only what the contract guarantees is asserted: proved bounds hold.

/// The solid NURBS ball of radius 150 about the origin (an exact rational sphere), found from this file.
const std::string kNurbsBall =
    (std::filesystem::path(__FILE__).parent_path() / "../../demos/scenes/ball_r150.unurbs.json").string();

/// lower_bound <= truth <= upper_bound (a null bound is infinite) and lower_bound <= distance <= upper_bound.
void expectBoundsContain(const json& j, double truth, double slack = 1e-9) {
  ASSERT_TRUE(j.contains("distance")) << j.dump();
  const double d = j["distance"].get<double>();
  if (j["lower_bound"].is_number()) {
    EXPECT_LE(j["lower_bound"].get<double>(), truth + slack) << j.dump();
    EXPECT_LE(j["lower_bound"].get<double>(), d) << j.dump();
  }
  if (j["upper_bound"].is_number()) {
    EXPECT_GE(j["upper_bound"].get<double>(), truth - slack) << j.dump();
    EXPECT_GE(j["upper_bound"].get<double>(), d) << j.dump();
  }
}

const std::vector<std::string> kOverlappingSpheres = {"distance", "sphere:r=1", "sphere:r=1", "--pose-b",
                                                      "0 0 1.5 1 0 0 0"};  // -0.5
const std::vector<std::string> kSeparatedSpheres = {"distance", "sphere:r=1", "sphere:r=0.5", "--pose-b",
                                                    "3 4 0 1 0 0 0"};  // 3.5

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

TEST(CliDial, ComputeOverlapGivesTheProvedVerdict) {
  const json in = queryJson(with(kOverlappingSpheres, {"--compute", "overlap"}));
  EXPECT_LE(in.at("distance").get<double>(), 0) << in.dump();
  EXPECT_EQ(in.at("status"), "certified") << in.dump();
  expectBoundsContain(in, -0.5);

  const json apart = queryJson(with(kSeparatedSpheres, {"--compute", "overlap"}));
  ASSERT_TRUE(apart.at("lower_bound").is_number()) << apart.dump();
  EXPECT_GT(apart.at("lower_bound").get<double>(), 0) << apart.dump();
  EXPECT_GT(apart.at("distance").get<double>(), 0) << apart.dump();
  expectBoundsContain(apart, 3.5);
}

TEST(CliDial, ComputeSeparationMeasuresTheGapAndProvesAnOverlap) {
  const json apart = queryJson(with(kSeparatedSpheres, {"--compute", "separation"}));
  EXPECT_NEAR(apart.at("distance").get<double>(), 3.5, 1e-9) << apart.dump();
  expectBoundsContain(apart, 3.5);

  const json in = queryJson(with(kOverlappingSpheres, {"--compute", "separation"}));
  ASSERT_TRUE(in.at("upper_bound").is_number()) << in.dump();
  EXPECT_LE(in.at("upper_bound").get<double>(), 0) << in.dump();
  expectBoundsContain(in, -0.5);

  // The default, spelt out, is the full query.
  const json full = queryJson(with(kOverlappingSpheres, {"--compute", "signed-distance"}));
  EXPECT_NEAR(full.at("distance").get<double>(), -0.5, 1e-9) << full.dump();
}

TEST(CliDial, RelativeToleranceKeepsProvedBounds) {
  // Two unit spheres 100 apart: at --rel-tol 0.1 the answer may be up to 10 off, but its bounds still hold.
  const json j = queryJson({"distance", "sphere:r=1", "sphere:r=1", "--pose-b", "102 0 0 1 0 0 0", "--rel-tol",
                            "0.1", "--tol", "0"});
  expectBoundsContain(j, 100);
  EXPECT_NEAR(j.at("distance").get<double>(), 100, 10 + 1e-9) << j.dump();
}

TEST(CliDial, MaxIterationsKeepsHonestBounds) {
  for (const char* n : {"1", "3", "100000"}) {
    SCOPED_TRACE(n);
    expectBoundsContain(queryJson({"distance", "sphere:r=0.5", "box:hx=1,hy=2,hz=3", "--pose-a", "0 0 5 1 0 0 0",
                                   "--pose-b", "0 0 0 0.7071067811865476 0.7071067811865476 0 0",
                                   "--max-iterations", n}),
                        2.5);
    expectBoundsContain(queryJson({"distance", kNurbsBall, "sphere:r=50", "--pose-b", "300 0 0 1 0 0 0",
                                   "--max-iterations", n}),
                        100);
  }
}

TEST(CliDial, DetailKeepsBoundsOnTheModelsThemselves) {
  // The NURBS ball (r = 150) against a sphere of radius 50 apart by 100 and overlapping by 30, A or B coarsened
  // (one case at 0.01: its stand-in takes seconds to build).
  struct Case {
    std::vector<std::string> args;
    double truth;
  };
  const std::vector<Case> cases = {
      {{"distance", kNurbsBall, "sphere:r=50", "--pose-b", "300 0 0 1 0 0 0", "--detail-a", "0.01"}, 100},
      {{"distance", kNurbsBall, "sphere:r=50", "--pose-b", "300 0 0 1 0 0 0", "--detail-a", "1"}, 100},
      {{"distance", kNurbsBall, "sphere:r=50", "--pose-b", "170 0 0 1 0 0 0", "--detail-a", "0.1"}, -30},
      {{"distance", "sphere:r=50", kNurbsBall, "--pose-a", "0 -300 0 1 0 0 0", "--detail-b", "0.1"}, 100},
      {{"distance", "sphere:r=50", kNurbsBall, "--pose-a", "0 0 199 1 0 0 0", "--detail-b", "0.5", "--detail-a",
        "0.01"}, -1},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.args.back());
    expectBoundsContain(queryJson(c.args), c.truth);
  }
}

// ---------------------------------------------------------------- info

TEST(CliInfo, JsonDescribesTheModel) {
  std::string raw;
  const json j = queryJson({"info", "box:hx=1,hy=2,hz=3"}, &raw);
  EXPECT_EQ(j.at("type"), "box");
  EXPECT_TRUE(j.at("description").is_string());
  EXPECT_EQ(j.at("solid"), true);
  EXPECT_EQ(j.at("convex"), true);
  EXPECT_EQ(j.at("bounded"), true);
  EXPECT_EQ(vec(j.at("aabb").at("min")), Eigen::Vector3d(-1, -2, -3));
  EXPECT_EQ(vec(j.at("aabb").at("max")), Eigen::Vector3d(1, 2, 3));
  EXPECT_GE(j.at("bounding_sphere").at("radius").get<double>(), std::sqrt(14.0) - 1e-12);
  EXPECT_TRUE(j.at("memory_bytes").is_number_integer());
  EXPECT_GT(j.at("memory_bytes").get<long long>(), 0);

  const json torus = queryJson({"info", "torus:R=1,r=0.25"});
  EXPECT_EQ(torus.at("type"), "torus");
  EXPECT_EQ(torus.at("convex"), false);

  // A half-space is unbounded: its box has no finite corners (null), and it says so.
  const json plane = queryJson({"info", "plane:nx=0,ny=0,nz=1,d=0"});
  EXPECT_EQ(plane.at("type"), "plane");
  EXPECT_EQ(plane.at("bounded"), false);
  EXPECT_TRUE(plane.at("aabb").at("max").at(0).is_null());
}

TEST(CliInfo, NurbsConvexityIsProvedOrExplained) {
  EXPECT_EQ(queryJson({"info", kNurbsBall}).at("convex"), true);
  const std::string torus =
      (std::filesystem::path(__FILE__).parent_path() / "../data/nurbs/torus_occt_faces.igs").string();
  EXPECT_EQ(queryJson({"info", torus}).at("convex"), false);
  const Outcome r = run({"info", torus});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("convex       no: patch 0 curves toward its outward normal"), std::string::npos) << r.out;
}

TEST(CliInfo, HumanReadable) {
  const Outcome r = run({"info", "sphere:r=2"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (const char* word : {"type", "sphere", "solid", "convex", "memory", "aabb"})
    EXPECT_NE(r.out.find(word), std::string::npos) << word << " in\n" << r.out;
}

// ---------------------------------------------------------------- bad input

/// Scratch directory of this test process (removed by the test that uses it).
std::filesystem::path scratchDir() {
  return std::filesystem::temp_directory_path() / ("unidist_cli_test_" + std::to_string(::getpid()));
}

/// A scratch file for the file-related bad inputs.
std::string scratchFile(const std::string& name, const std::string& content) {
  std::filesystem::create_directories(scratchDir());
  const std::filesystem::path p = scratchDir() / name;
  std::ofstream(p) << content;
  return p.string();
}

struct BadCase {
  const char* what;
  std::vector<std::string> args;
  std::string fragment;  ///< the message must name the problem
};

std::vector<BadCase> badCases() {
  const std::string garbageObj = scratchFile("garbage.obj", "v 1 2 x\nthis is not obj\nf 1 2 3\n");
  const std::string unknownExt = scratchFile("model.foo", "solid\n");
  const std::string S = "sphere:r=1", B = "box:hx=1,hy=1,hz=1";
  return {
      {"unknown primitive", {"distance", "pyramid:r=1", S}, "pyramid"},
      {"unknown primitive in B", {"distance", S, "blob:r=1"}, "blob"},
      {"missing key", {"distance", "box:hx=1,hy=1", S}, "missing key 'hz'"},
      {"missing all keys", {"distance", "sphere:", S}, "missing key 'r'"},
      {"duplicate key", {"distance", "sphere:r=1,r=2", S}, "duplicate key 'r'"},
      {"unknown key", {"distance", "sphere:r=1,q=2", S}, "unknown key 'q'"},
      {"key case", {"distance", "torus:r=1,R=0.5,x=1", S}, "unknown key 'x'"},
      {"spaces in spec", {"distance", "sphere: r=1", S}, "unknown key ' r'"},
      {"zero size", {"distance", "sphere:r=0", S}, "r must be > 0"},
      {"negative size", {"distance", S, "capsule:r=1,h=-1"}, "h must be > 0"},
      {"torus tube too thick", {"distance", "torus:R=1,r=2", S}, "r must be < R"},
      {"zero plane normal", {"distance", "plane:nx=0,ny=0,nz=0,d=0", S}, "normal"},
      {"NaN in spec", {"distance", "sphere:r=nan", S}, "'nan' is not a number"},
      {"Inf in spec", {"distance", S, "box:hx=inf,hy=1,hz=1"}, "'inf' is not a number"},
      {"overflow in spec", {"distance", S, "box:hx=1e999,hy=1,hz=1"}, "out of range"},
      {"hex in spec", {"distance", "sphere:r=0x1", S}, "'0x1' is not a number"},
      {"Inf in pose", {"distance", S, B, "--pose-a", "inf 0 0 1 0 0 0"}, "--pose-a tx"},
      {"NaN in pose", {"distance", S, B, "--pose-b", "0 0 0 nan 0 0 0"}, "--pose-b qw"},
      {"short pose", {"distance", S, B, "--pose-a", "0 0 0 1 0 0"}, "expected 7 numbers"},
      {"long pose", {"distance", S, B, "--pose-b", "0 0 0 1 0 0 0 0"}, "got 8"},
      {"zero quaternion", {"distance", S, B, "--pose-a", "1 2 3 0 0 0 0"}, "zero quaternion"},
      {"junk pose", {"distance", S, B, "--pose-a", "a b c d e f g"}, "--pose-a tx"},
      {"empty pose", {"distance", S, B, "--pose-a", ""}, ""},
      {"NaN --tol", {"distance", S, B, "--tol", "nan"}, "--tol"},
      {"Inf --tol", {"distance", S, B, "--tol", "inf"}, "--tol"},
      {"negative --tol", {"distance", S, B, "--tol", "-1e-6"}, "--tol must be >= 0"},
      {"junk --tol", {"distance", S, B, "--tol", "1e-6x"}, "--tol"},
      {"unknown --compute", {"distance", S, B, "--compute", "fast"}, "--compute must be 'overlap', 'separation'"},
      {"empty --compute", {"distance", S, B, "--compute", ""}, "--compute"},
      {"--compute case", {"distance", S, B, "--compute", "Overlap"}, "'Overlap'"},
      {"negative --rel-tol", {"distance", S, B, "--rel-tol", "-1"}, "--rel-tol must be >= 0"},
      {"NaN --rel-tol", {"distance", S, B, "--rel-tol", "nan"}, "--rel-tol"},
      {"Inf --rel-tol", {"distance", S, B, "--rel-tol", "inf"}, "--rel-tol"},
      {"zero --max-iterations", {"distance", S, B, "--max-iterations", "0"}, "--max-iterations must be"},
      {"negative --max-iterations", {"distance", S, B, "--max-iterations", "-5"}, "--max-iterations"},
      {"fractional --max-iterations", {"distance", S, B, "--max-iterations", "2.5"}, "--max-iterations"},
      {"huge --max-iterations", {"distance", S, B, "--max-iterations", "1e10"}, "--max-iterations"},
      {"junk --max-iterations", {"distance", S, B, "--max-iterations", "ten"}, "--max-iterations"},
      {"NaN --detail-a", {"distance", S, B, "--detail-a", "nan"}, "--detail-a"},
      {"negative --detail-a", {"distance", S, B, "--detail-a", "-0.01"}, "--detail-a must be >= 0"},
      {"Inf --detail-b", {"distance", S, B, "--detail-b", "inf"}, "--detail-b"},
      {"negative --detail-b", {"distance", S, B, "--detail-b=-1"}, "--detail-b must be >= 0"},
      {"empty --detail-b", {"distance", S, B, "--detail-b", ""}, "--detail-b"},
      {"--compute with --pd raster", {"distance", B, B, "--pd", "raster", "--compute", "overlap"},
       "--compute overlap needs --pd exact"},
      {"--detail-a with --pd raster", {"distance", B, B, "--pd", "raster", "--detail-a", "0.1"}, "--detail-a"},
      {"--rel-tol with --pd raster", {"distance", B, B, "--pd", "raster", "--rel-tol", "0.1"}, "--rel-tol"},
      {"negative --inflate-a", {"distance", S, B, "--inflate-a", "-0.5"}, "--inflate-a must be >= 0"},
      {"negative --inflate-b", {"distance", S, B, "--inflate-b=-1"}, "--inflate-b must be >= 0"},
      {"NaN --inflate-b", {"distance", S, B, "--inflate-b", "nan"}, "--inflate-b"},
      {"Inf --inflate-a", {"distance", S, B, "--inflate-a", "inf"}, "--inflate-a"},
      {"missing file", {"distance", "/nonexistent/dir/model.obj", S}, "/nonexistent/dir/model.obj"},
      {"missing file without extension", {"distance", S, "nosuchfile"}, "nosuchfile"},
      {"malformed or unsupported file", {"distance", garbageObj, S}, garbageObj},
      {"unknown file extension", {"distance", unknownExt, S}, "unknown model format"},
      {"directory as model", {"distance", "/", S}, "directory"},
      {"plane-plane pair", {"distance", "plane:nx=0,ny=0,nz=1,d=0", "plane:nx=1,ny=0,nz=0,d=0"}, "not supported"},
      {"unknown subcommand", {"frobnicate", S, B}, "frobnicate"},
      {"no subcommand", {}, "subcommand"},
      {"only an option", {"--json"}, ""},
      {"unknown option", {"distance", S, B, "--frobnicate"}, "--frobnicate"},
      {"unknown short option", {"distance", S, B, "-q"}, "-q"},
      {"missing argument B", {"distance", S}, "B"},
      {"missing arguments", {"distance"}, "A"},
      {"extra argument", {"distance", S, B, "sphere:r=2"}, "sphere:r=2"},
      {"option without value", {"distance", S, B, "--tol"}, "--tol"},
      {"info without model", {"info"}, "A"},
      {"info with bad spec", {"info", "cone:r=1"}, "missing key 'h'"},
      {"info with missing file", {"info", "/nonexistent.stl", "--json"}, "/nonexistent.stl"},
      {"bad input with --json", {"distance", "sphere:r=-1", S, "--json"}, "r must be > 0"},
  };
}

TEST(CliBadInput, EveryClassExitsTwoWithOneErrorLine) {
  const std::string prefix = "unidist: error: ";
  for (const BadCase& c : badCases()) {
    SCOPED_TRACE(c.what);
    const Outcome r = run(c.args);
    const std::string info = describe(c.args, r);
    EXPECT_EQ(r.signal, 0) << info;
    EXPECT_EQ(r.exitCode, 2) << info;
    EXPECT_EQ(r.out, "") << info;
    ASSERT_FALSE(r.err.empty()) << info;
    EXPECT_EQ(r.err.rfind(prefix, 0), 0u) << info;
    EXPECT_EQ(r.err.back(), '\n') << info;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "more than one line: " << info;
    EXPECT_GT(r.err.size(), prefix.size() + 2) << "the message must name the problem: " << info;
    EXPECT_NE(r.err.find(c.fragment), std::string::npos) << "expected '" << c.fragment << "' in: " << info;
  }
  std::filesystem::remove_all(scratchDir());
}

TEST(CliBadInput, RepeatedOptionIsAnErrorOrTheLastOneWins) {
  // CLI11 may reject a repeated single-value option; it must never crash or print two answers.
  const Outcome r = run({"distance", "sphere:r=1", "sphere:r=1", "--pose-b", "3 0 0 1 0 0 0", "--tol", "nan",
                     "--tol", "1e-9", "--json"});
  if (r.exitCode == 0) {
    EXPECT_EQ(r.out.find('\n'), r.out.size() - 1);
  } else {
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
  }
}

}  // namespace
