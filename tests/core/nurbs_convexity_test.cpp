// The convexity certificate of NURBS solids (core/src/nurbs/convexity_certificate.h): proved for convex solids
// of every kind of seam (smooth seams and poles of a rational sphere and ellipsoid, the convex creases of a box
// and of a capped cylinder), at any scale; refused, naming the condition, for a torus and a dented sphere
// (curving toward the outward normal), a sphere with a point of a seam pulled in (creases folding outward), a
// can with a sunk conical top, two separate balls in one model, and open surfaces.
#include "bench/ellipsoid_truth.h"
#include "nurbs/convex_support.h"
#include "nurbs_fixtures.h"
#include "unidist/nurbs.h"

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

namespace unidist {
namespace {

using nurbs_fixtures::Net;
using nurbs_fixtures::Point2W;

/// A solid of revolution about z from a degree-1 profile (radius, height), creases at the profile's points.
NurbsSurface revolvedPolyline(const std::vector<Point2W>& profile) {
  std::vector<double> knots = {0, 0};
  const int spans = static_cast<int>(profile.size()) - 1;
  for (int k = 1; k < spans; ++k) knots.push_back(static_cast<double>(k) / spans);
  knots.insert(knots.end(), {1, 1});
  return {2, 1, nurbs_fixtures::circleKnots(), knots, nurbs_fixtures::revolve(profile, 1, Eigen::Vector3d::Zero())};
}

/// The sphere's net with every point (and its weight) kept, the Euclidean points mapped by f.
template <class F>
NurbsSurface mappedSphere(double radius, F f) {
  const NurbsSurface s = nurbs_fixtures::sphereSurface(radius);
  Net net(static_cast<std::size_t>(s.countU()));
  for (int i = 0; i < s.countU(); ++i)
    for (int j = 0; j < s.countV(); ++j) {
      const Eigen::Vector4d c = s.controlPoint(i, j);
      const Eigen::Vector3d p = f(Eigen::Vector3d(c.head<3>()), i, j);
      net[static_cast<std::size_t>(i)].emplace_back(p.x(), p.y(), p.z(), c[3]);
    }
  return {s.degreeU(), s.degreeV(), s.knotsU(), s.knotsV(), net};
}

std::string whyNot(const NurbsModel& m) {
  std::string why;
  EXPECT_FALSE(m.provedConvex(&why));
  return why;
}

TEST(NurbsConvexity, ConvexSolidsAreProvedAtEveryScale) {
  for (double scale : {1e-4, 1.0, 1e4}) {
    SCOPED_TRACE(scale);
    std::string why;
    const NurbsModel sphere({nurbs_fixtures::sphereSurface(scale)}, true);
    EXPECT_TRUE(sphere.provedConvex(&why)) << why;
    const NurbsModel ellipsoid({ellipsoid_truth::surface(scale * Eigen::Vector3d(2, 1, 0.3))}, true);
    EXPECT_TRUE(ellipsoid.provedConvex(&why)) << why;
    const NurbsModel box(nurbs_fixtures::boxPatches(Eigen::Vector3d(1, 2, 0.5) * scale), true);
    EXPECT_TRUE(box.provedConvex(&why)) << why;
    const NurbsModel can({revolvedPolyline({{0, -scale, 1}, {scale, -scale, 1}, {scale, scale, 1}, {0, scale, 1}})}, true);
    EXPECT_TRUE(can.provedConvex(&why)) << why;
  }
}

TEST(NurbsConvexity, NonConvexSolidsAreRefusedWithTheReason) {
  // The torus's inner half curves toward its outward normal.
  EXPECT_NE(whyNot(NurbsModel({nurbs_fixtures::torusSurface()}, true)).find("curves toward its outward normal"),
            std::string::npos);
  // A control point inside a patch pulled in by 70 %: a dent in that patch.
  const NurbsModel dented({mappedSphere(1, [](const Eigen::Vector3d& p, int i, int j) {
                            return i == 1 && j == 1 ? Eigen::Vector3d(0.3 * p) : p;
                          })},
                          true);
  EXPECT_NE(whyNot(dented).find("curves toward its outward normal"), std::string::npos);
  // A point of the equator (a patch corner: the seams there) pulled in by 40 %: the seams fold outward.
  const NurbsModel creased({mappedSphere(1, [](const Eigen::Vector3d& p, int i, int j) {
                             return i == 2 && j == 2 ? Eigen::Vector3d(0.6 * p) : p;
                           })},
                           true);
  EXPECT_NE(whyNot(creased).find("folds outward"), std::string::npos);
  // A can whose top is a cone pushed into it: the top curves toward its outward normal.
  const NurbsModel dimpled({revolvedPolyline({{0, -1, 1}, {1, -1, 1}, {1, 1, 1}, {0, 0.5, 1}})}, true);
  EXPECT_NE(whyNot(dimpled).find("curves toward its outward normal"), std::string::npos);
  const NurbsModel twoBalls({nurbs_fixtures::sphereSurface(1, Eigen::Vector3d(-2, 0, 0)),
                             nurbs_fixtures::sphereSurface(1, Eigen::Vector3d(2, 0, 0))},
                            true);
  EXPECT_NE(whyNot(twoBalls).find("not connected"), std::string::npos);
  EXPECT_NE(whyNot(NurbsModel({nurbs_fixtures::sphereSurface()}, false)).find("open"), std::string::npos);
  EXPECT_FALSE(NurbsModel({nurbs_fixtures::wavySurface()}, false).provedConvex());
}

// The support map of proved-convex models (nurbs/convex_support.h: the highest corner when it tops the control
// points, else a local ascent) against the analytic support of an ellipsoid and a box, in random directions and
// along the axes (where the support lies on a seam, a pole or a vertex), at three scales.
TEST(NurbsConvexity, ConvexSupportIsTheSupport) {
  std::mt19937 rng(5);
  std::normal_distribution<double> g;
  for (double scale : {1e-4, 1.0, 1e4}) {
    const Eigen::Vector3d axes = scale * Eigen::Vector3d(1.0, 0.6, 0.35), half = scale * Eigen::Vector3d(1, 2, 0.5);
    const NurbsModel ellipsoid({ellipsoid_truth::surface(axes)}, true);
    const NurbsModel box(nurbs_fixtures::boxPatches(half), true);
    ASSERT_TRUE(ellipsoid.provedConvex() && box.provedConvex());
    std::vector<Eigen::Vector3d> directions;
    for (int k = 0; k < 3; ++k)
      for (double sign : {1.0, -1.0}) directions.push_back(sign * Eigen::Vector3d::Unit(k));
    for (int k = 0; k < 500; ++k) directions.push_back(Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized());
    for (const Eigen::Vector3d& d : directions) {
      SCOPED_TRACE(::testing::Message() << "scale " << scale << " d " << d.transpose());
      const double ellipsoidTruth = axes.cwiseProduct(d).norm(), boxTruth = half.dot(d.cwiseAbs());
      EXPECT_NEAR(d.dot(nurbs::convexSupport(ellipsoid, d)), ellipsoidTruth, 1e-13 * scale);
      EXPECT_NEAR(d.dot(ellipsoid.support(d)), ellipsoidTruth, 1e-12 * scale);
      EXPECT_NEAR(d.dot(nurbs::convexSupport(box, d)), boxTruth, 1e-13 * scale);
      EXPECT_NEAR(d.dot(box.support(d)), boxTruth, 1e-13 * scale);
    }
  }
}

}  // namespace
}  // namespace unidist
