// `unidist distance --pd raster [--resolution N]`: unions of convex pieces (OBJ groups, box specs) answered by
// the image-space penetration depth (docs/raster.md), with the contract's output and the usual bad-input rules.
#include "run_unidist.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <string>
#include <vector>

namespace {

using nlohmann::json;
using unidist::testing::Outcome;
using unidist::testing::run;

const std::string kBlock = std::string(UNIDIST_PIECES_DIR) + "/l_block.obj";

json distanceJson(std::vector<std::string> args) {
  args.insert(args.begin(), "distance");
  args.push_back("--json");
  const Outcome r = run(args);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  try {
    return json::parse(r.out);
  } catch (const std::exception& e) {
    ADD_FAILURE() << "stdout is not JSON: " << r.out << " / " << r.err;
    return json::object();
  }
}

TEST(CliRaster, CubeInTheNotchOfTheLBlockGetsTheUnionsPenetrationDepth) {
  const json j = distanceJson({kBlock, "box:hx=0.25,hy=0.25,hz=0.25", "--pose-b", "1.15 1.15 0.5 1 0 0 0", "--pd",
                               "raster", "--resolution", "128"});
  const double truth = -0.1 * std::sqrt(2.0);
  EXPECT_NEAR(j.at("distance").get<double>(), truth, 2e-3);
  EXPECT_LE(j.at("lower_bound").get<double>(), truth + 1e-12);
  EXPECT_GE(j.at("upper_bound").get<double>(), truth - 1e-12);
  EXPECT_LE(j.at("upper_bound").get<double>(), -0.1 + 1e-9);  // at least the deepest single pair
  const std::vector<double> n = j.at("normal").get<std::vector<double>>();
  EXPECT_NEAR(n[0], std::sqrt(0.5), 0.03);
  EXPECT_NEAR(n[1], std::sqrt(0.5), 0.03);
  const std::vector<double> a = j.at("point_a").get<std::vector<double>>(), b = j.at("point_b").get<std::vector<double>>();
  const double d = j.at("distance").get<double>();
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(b[i] - a[i], d * n[i], 1e-9);
}

TEST(CliRaster, SeparatedUnionsGetTheExactDistance) {
  const json j = distanceJson({kBlock, "box:hx=0.25,hy=0.25,hz=0.25", "--pose-b", "1.5 1.5 0.5 1 0 0 0", "--pd", "raster"});
  EXPECT_NEAR(j.at("distance").get<double>(), 0.25, 1e-9);
  EXPECT_EQ(j.at("status").get<std::string>(), "certified");
}

TEST(CliRaster, BadCombinationsAndNonConvexPiecesAreOneLineErrors) {
  const std::string notConvex = std::string(UNIDIST_PIECES_DIR) + "/not_convex.obj";
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"distance", kBlock, kBlock, "--pd", "fast"}, "--pd must be 'exact' or 'raster'"},
      {{"distance", kBlock, kBlock, "--resolution", "64"}, "--resolution needs --pd raster"},
      {{"distance", kBlock, kBlock, "--pd", "raster", "--resolution", "3"}, "--resolution must be"},
      {{"distance", kBlock, kBlock, "--pd", "raster", "--resolution", "64.5"}, "--resolution must be"},
      {{"distance", kBlock, kBlock, "--pd", "raster", "--inflate-a", "0.1"}, "--inflate"},
      {{"distance", notConvex, kBlock, "--pd", "raster"}, "A: convex piece 'l_prism' is not convex"},
      {{"distance", kBlock, "sphere:r=1", "--pd", "raster"}, "B: "},
  };
  for (const auto& [args, fragment] : cases) {
    const Outcome r = run(args);
    EXPECT_EQ(r.exitCode, 2) << args[1] << " " << r.err;
    EXPECT_TRUE(r.out.empty());
    EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
  }
}

}  // namespace
