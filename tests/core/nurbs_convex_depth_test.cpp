// Penetration depth of NURBS solids proved convex (GJK/EPA on their support maps) against independent truth:
// rational ellipsoids in any orientation against the minimum of their analytic support functions
// (depth = min over unit n of h_A(n) + h_B(−n)), from the deepest overlap to touching, at scales 1e-4 to 1e4;
// a NURBS ball against a box primitive and a sphere primitive (one point query) against their closed forms.
// Every answer certified, its bounds holding the truth, within the tolerance.
#include "bench/ellipsoid_truth.h"
#include "nurbs_fixtures.h"
#include "unidist/distance.h"
#include "unidist/nurbs.h"
#include "unidist/primitives.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace unidist {
namespace {

using Vec = Eigen::Vector3d;

Eigen::Isometry3d randomPose(std::mt19937& rng, double reach) {
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::Quaterniond(Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
  X.translation() = reach * Vec(u(rng), u(rng), u(rng));
  return X;
}

TEST(NurbsConvexDepth, EllipsoidsAgainstTheirSupportFunctions) {
  std::mt19937 rng(7);
  int cases = 0;
  for (double scale : {1e-4, 1.0, 1e4}) {
    const ellipsoid_truth::Ellipsoid a{scale * Vec(1.0, 0.6, 0.35), Eigen::Isometry3d::Identity()};
    const ellipsoid_truth::Ellipsoid bShape{scale * Vec(0.8, 0.8, 0.3), Eigen::Isometry3d::Identity()};
    const NurbsModel ma({ellipsoid_truth::surface(a.axes)}, true), mb({ellipsoid_truth::surface(bShape.axes)}, true);
    ASSERT_TRUE(ma.provedConvex() && mb.provedConvex());
    for (int k = 0; k < 20; ++k) {
      const ellipsoid_truth::Ellipsoid b{bShape.axes, randomPose(rng, 0.8 * scale)};
      const double truth = ellipsoid_truth::depth(a, b);
      if (!(truth > 0)) continue;  // apart: the separation search's case, tested elsewhere
      DistanceOptions options;
      options.tolerance = 1e-9 * scale;
      const DistanceResult r = distance(ma, Eigen::Isometry3d::Identity(), mb, b.pose, options);
      SCOPED_TRACE(::testing::Message() << "scale " << scale << " case " << k << " depth " << truth);
      EXPECT_EQ(r.status, Status::Certified);
      EXPECT_NEAR(r.distance, -truth, options.tolerance);
      EXPECT_LE(r.lowerBound, -truth + 1e-12 * scale);
      EXPECT_GE(r.upperBound, -truth - 1e-12 * scale);
      EXPECT_NEAR((r.pointB - r.pointA).norm(), truth, options.tolerance);
      ++cases;
    }
  }
  EXPECT_GE(cases, 30);
}

TEST(NurbsConvexDepth, BallsFromDeepToTouching) {
  const NurbsModel ball({nurbs_fixtures::sphereSurface(1)}, true);
  for (double gap : {0.02, 0.54, 1.0, 1.5, 1.999999, 2.0}) {
    const Vec centre = gap * Vec(0.48, -0.6, 0.64);
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation() = centre;
    const DistanceResult r = distance(ball, Eigen::Isometry3d::Identity(), ball, X, DistanceOptions{});
    SCOPED_TRACE(gap);
    const double tol = 1e-9 * ball.localBounds().diagonal();
    EXPECT_EQ(r.status, Status::Certified);
    EXPECT_NEAR(r.distance, gap - 2, tol);
    EXPECT_LE(r.lowerBound, gap - 2 + 1e-12);
    EXPECT_GE(r.upperBound, gap - 2 - 1e-12);
    if (gap < 1.9) {
      EXPECT_GT(r.normal.dot(centre.normalized()), 1 - 1e-6);  // B leaves along the centres' line
    }
  }
}

TEST(NurbsConvexDepth, SpherePrimitiveDeepInANurbsBallIsOnePointQuery) {
  const NurbsModel ball({nurbs_fixtures::sphereSurface(1)}, true);
  const Sphere probe(0.3);
  for (double offset : {0.05, 0.5, 0.9, 1.2}) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation() = offset * Vec(0, 0.6, 0.8);
    const DistanceResult r = distance(probe, X, ball, Eigen::Isometry3d::Identity(), DistanceOptions{});
    SCOPED_TRACE(offset);
    EXPECT_EQ(r.status, Status::Certified);
    EXPECT_STREQ(r.method, "sphere-point-query");
    EXPECT_NEAR(r.distance, offset - 1.3, 1e-9);
  }
}

TEST(NurbsConvexDepth, BallInABox) {
  const NurbsModel ball({nurbs_fixtures::sphereSurface(0.5)}, true);
  const Box box(Vec(1, 2, 3));
  // Centre inside the box: out through the nearest face, radius plus the face's distance; outside: the radius
  // minus the centre's distance.
  for (const Vec& c : {Vec(0.7, 0.1, -0.4), Vec(0.2, 1.9, 0.3), Vec(1.3, 0.5, 0.5), Vec(1.2, 2.2, 0)}) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation() = c;
    const Vec clamped = c.cwiseMax(-box.halfExtents()).cwiseMin(box.halfExtents());
    const double inside = (box.halfExtents() - c.cwiseAbs()).minCoeff();
    const double truth = inside > 0 ? -(0.5 + inside) : (clamped - c).norm() - 0.5;
    const DistanceResult r = distance(box, Eigen::Isometry3d::Identity(), ball, X, DistanceOptions{});
    SCOPED_TRACE(::testing::Message() << c.transpose());
    EXPECT_EQ(r.status, Status::Certified);
    EXPECT_NEAR(r.distance, truth, 1e-8);
    EXPECT_LE(r.lowerBound, truth + 1e-12);
    EXPECT_GE(r.upperBound, truth - 1e-12);
  }
}

}  // namespace
}  // namespace unidist
