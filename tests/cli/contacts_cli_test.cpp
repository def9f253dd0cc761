// `unidist contacts` as a black box: the JSON shape ({"contacts": [{point_a, point_b, normal, distance,
// error_bound}]}), the
// invariant point_b − point_a = distance · normal with 17 significant digits, the known four corners of a box
// resting on a box, --margin and --max-contacts, the text form (one line per contact), and bad input (exit 2,
// nothing on stdout, one stderr line "unidist: error: ...").
#include <Eigen/Core>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "run_unidist.h"

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace {

using nlohmann::json;
using unidist::testing::Outcome;
using unidist::testing::run;

Eigen::Vector3d vec(const json& j) { return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()}; }

json contactsOf(const std::vector<std::string>& args) {
  const Outcome r = run(args);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j.size(), 1u);
  EXPECT_TRUE(j.at("contacts").is_array());
  for (const json& c : j.at("contacts")) {
    EXPECT_EQ(c.size(), 5u);
    const Eigen::Vector3d a = vec(c.at("point_a")), b = vec(c.at("point_b")), n = vec(c.at("normal"));
    const double d = c.at("distance").get<double>();
    const double e = c.at("error_bound").get<double>();
    EXPECT_TRUE(e >= 0 && std::isfinite(e)) << e;
    EXPECT_NEAR(n.norm(), 1, 1e-12);
    EXPECT_LE((b - a - d * n).norm(), 1e-9);
  }
  return j.at("contacts");
}

TEST(CliContacts, BoxOnBoxGivesFourCornersAsJson) {
  const json cs = contactsOf({"contacts", "box:hx=1,hy=1,hz=1", "box:hx=0.5,hy=0.5,hz=0.5", "--pose-b",
                              "0.2 0 1.5 1 0 0 0.1", "--json"});
  ASSERT_EQ(cs.size(), 4u);
  for (const json& c : cs) {
    EXPECT_NEAR(c.at("distance").get<double>(), 0, 1e-12);
    EXPECT_LE(c.at("error_bound").get<double>(), 1e-12);  // closed-form box corners: rounding only
    EXPECT_NEAR(vec(c.at("normal")).z(), 1, 1e-12);
    EXPECT_NEAR(vec(c.at("point_a")).z(), 1, 1e-12);
  }
}

TEST(CliContacts, MarginAndMaxContacts) {
  // 1e-3 apart: nothing at the default margin 0, four corners within 0.01, the deepest-first two with a cap.
  const std::vector<std::string> base = {"contacts", "box:hx=1,hy=1,hz=1", "box:hx=0.5,hy=0.5,hz=0.5", "--pose-b",
                                         "0 0 1.501 1 0 0 0", "--json"};
  EXPECT_EQ(contactsOf(base).size(), 0u);
  std::vector<std::string> withMargin = base;
  withMargin.insert(withMargin.end(), {"--margin", "0.01"});
  const json four = contactsOf(withMargin);
  ASSERT_EQ(four.size(), 4u);
  EXPECT_NEAR(four[0].at("distance").get<double>(), 1e-3, 1e-12);
  withMargin.insert(withMargin.end(), {"--max-contacts", "2"});
  EXPECT_EQ(contactsOf(withMargin).size(), 2u);
}

TEST(CliContacts, SeventeenDigitsAndTextForm) {
  const Outcome j = run({"contacts", "sphere:r=1", "sphere:r=1", "--pose-b", "1.9 0 0 1 0 0 0", "--json"});
  ASSERT_EQ(j.exitCode, 0);
  EXPECT_NE(j.out.find("-0.10000000000000009"), std::string::npos) << j.out;  // %.17g of 1.9 − 2
  const Outcome t = run({"contacts", "sphere:r=1", "sphere:r=1", "--pose-b", "1.9 0 0 1 0 0 0"});
  ASSERT_EQ(t.exitCode, 0);
  EXPECT_EQ(std::count(t.out.begin(), t.out.end(), '\n'), 1);
  EXPECT_EQ(t.out.rfind("distance -0.10000000000000009", 0), 0u) << t.out;
}

TEST(CliContacts, MeshFileAgainstPlane) {
  const json cs = contactsOf({"contacts", "plane:nx=0,ny=0,nz=1,d=0", UNIDIST_MODELS "/icosphere.stl", "--pose-b",
                              "0 0 0.99 1 0 0 0", "--margin", "0.1", "--json"});
  ASSERT_GE(cs.size(), 1u);
  EXPECT_LT(cs[0].at("distance").get<double>(), 0);
  EXPECT_NEAR(vec(cs[0].at("normal")).z(), 1, 1e-12);  // the mesh (B) must move up
}

TEST(CliContacts, DialOptions) {
  // Unit spheres overlapping by 0.1: one contact at -0.1 whatever the (valid) dial.
  const std::vector<std::string> base = {"contacts", "sphere:r=1", "sphere:r=1", "--pose-b", "1.9 0 0 1 0 0 0",
                                         "--json"};
  const std::vector<std::vector<std::string>> dials = {
      {"--tol", "1e-12"}, {"--tol", "0"}, {"--rel-tol", "0.1"}, {"--max-iterations", "1000"},
      {"--detail-a", "0", "--detail-b", "0"}, {"--tol", "1e-6", "--rel-tol", "0", "--max-iterations", "1"}};
  for (const auto& dial : dials) {
    SCOPED_TRACE(dial.front() + " " + dial.back());
    std::vector<std::string> args = base;
    args.insert(args.end(), dial.begin(), dial.end());
    const json cs = contactsOf(args);
    ASSERT_EQ(cs.size(), 1u);
    EXPECT_NEAR(cs[0].at("distance").get<double>(), -0.1, 1e-6);
  }
}

TEST(CliContacts, DetailOfANurbsBall) {
  // The NURBS ball (r = 150, an exact rational sphere) 0.5 from a sphere of radius 50; at --detail-a D the
  // contact is on a stand-in within D of the ball, so its distance is within D of 0.5.
  const std::string ball =
      (std::filesystem::path(__FILE__).parent_path() / "../../demos/scenes/ball_r150.unurbs.json").string();
  for (const char* detail : {"0", "0.1", "1"}) {
    SCOPED_TRACE(detail);
    const json cs = contactsOf({"contacts", ball, "sphere:r=50", "--pose-b", "200.5 0 0 1 0 0 0", "--margin", "1",
                                "--detail-a", detail, "--json"});
    ASSERT_GE(cs.size(), 1u);
    // The reported bound holds the truth and is the stand-in's deviation (<= D) plus the search's accuracy.
    const double d = cs[0].at("distance").get<double>(), e = cs[0].at("error_bound").get<double>();
    EXPECT_LE(std::abs(d - 0.5), e);
    EXPECT_LE(e, std::stod(detail) + 1e-6);
  }
}

TEST(CliContacts, BadInput) {
  const std::vector<std::vector<std::string>> cases = {
      {"contacts", "sphere:r=1"},
      {"contacts", "sphere:r=1", "sphere:r=-1"},
      {"contacts", "sphere:r=1", "sphere:r=1", "--margin", "-1"},
      {"contacts", "sphere:r=1", "sphere:r=1", "--margin", "nan"},
      {"contacts", "sphere:r=1", "sphere:r=1", "--margin", ""},
      {"contacts", "sphere:r=1", "sphere:r=1", "--max-contacts", "2.5"},
      {"contacts", "sphere:r=1", "sphere:r=1", "--max-contacts", "-1"},
      {"contacts", "sphere:r=1", "sphere:r=1", "--pose-a", "1 2 3"},
      {"contacts", "sphere:r=1", "sphere:r=1", "--tol", "-1"},
      {"contacts", "sphere:r=1", "sphere:r=1", "--tol", "nan"},
      {"contacts", "sphere:r=1", "sphere:r=1", "--rel-tol", "-1"},
      {"contacts", "sphere:r=1", "sphere:r=1", "--max-iterations", "0"},
      {"contacts", "sphere:r=1", "sphere:r=1", "--max-iterations", "1.5"},
      {"contacts", "sphere:r=1", "sphere:r=1", "--detail-a", "nan"},
      {"contacts", "sphere:r=1", "sphere:r=1", "--detail-b", "-0.1"},
      {"contacts", "sphere:r=1", "sphere:r=1", "--compute", "overlap"},
      {"contacts", "sphere:r=1", "/nonexistent/model.obj"},
      {"contacts", "plane:nx=0,ny=0,nz=1,d=0", "plane:nx=0,ny=0,nz=1,d=1"},
  };
  for (const auto& args : cases) {
    const Outcome r = run(args);
    SCOPED_TRACE(args.back());
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_EQ(r.err.rfind("unidist: error: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

}  // namespace
