// Penetration depth of a non-convex NURBS solid (the exact torus) against balls and a box, settled from the point
// where the surfaces meet: the deepest point near it and the escape along its normal (translation_depth.h,
// shallowDepth), with the full translation search behind it where that escape does not meet the depth.
// Truth: a ball of radius ρ centred at c overlaps the torus (core circle C, tube radius a) by exactly
// a + ρ − dist(c, C) while c is nearer C than the axis (the ball must leave the tube grown by ρ), along the line
// from C's nearest point to c; a box face lying across the tube's top overlaps by how far it sinks below the top.
// Scales 1e-4 to 1e4, random poses, depths from 1e-6 of the size to most of the tube. And a deep overlap of two
// tori, where balls inscribed at the escape's contact bound the depth (translation_depth.cpp).
#include "bench/nurbs_truth.h"
#include "nurbs_fixtures.h"
#include "unidist/distance.h"
#include "unidist/nurbs.h"
#include "unidist/primitives.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <utility>

namespace unidist {
namespace {

using Vec = Eigen::Vector3d;

Eigen::Isometry3d randomRotation(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::Quaterniond(Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
  return X;
}

/// B in A's orientation with its origin at p in A's frame.
Eigen::Isometry3d placedIn(const Eigen::Isometry3d& XA, const Vec& p) {
  Eigen::Isometry3d XB = XA;
  XB.translation() = XA * p;
  return XB;
}

/// The queries' options at a model scale: tolerance 1e-9 of it.
DistanceOptions atScale(double scale) {
  DistanceOptions opt;
  opt.tolerance = 1e-9 * scale;
  return opt;
}

/// The bracket holds the true signed distance −depth, and the value is within the tolerance of it.
void expectHolds(const DistanceResult& r, double depth, double tolerance) {
  EXPECT_LE(r.lowerBound, -depth + 1e-3 * tolerance);
  EXPECT_GE(r.upperBound, -depth - 1e-3 * tolerance);
  EXPECT_NEAR(r.distance, -depth, tolerance);
}

void expectDepth(const DistanceResult& r, double depth, const Vec& away, double tolerance) {
  EXPECT_EQ(r.status, Status::Certified) << r.method;
  expectHolds(r, depth, tolerance);
  EXPECT_GT(r.normal.dot(away), 1 - 1e-6) << "B leaves along the line from the core circle to the ball's centre";
  const double rounding = 64 * std::numeric_limits<double>::epsilon() * (r.pointA.norm() + r.pointB.norm());
  EXPECT_NEAR((r.pointB - r.pointA).dot(r.normal), r.distance, rounding);
}

TEST(NurbsShallowDepth, BallsSunkIntoTheTorusTubeGetTheirExactDepth) {
  const double R = 1, a = 0.25, rho = 0.4;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> angle(0, 2 * M_PI);
  const nurbs_truth::Circle core{Vec::Zero(), Vec::UnitZ(), R};
  for (double scale : {1e-4, 1.0, 1e4}) {
    const NurbsModel torus({nurbs_fixtures::torusSurface(R * scale, a * scale)}, true);
    const NurbsModel ball({nurbs_fixtures::sphereSurface(rho * scale)}, true);
    const Sphere sphere(rho * scale);
    const DistanceOptions opt = atScale(scale);
    for (double depth : {1e-6, 1e-3, 0.05, 0.3}) {
      // The ball's centre off the tube at a random place around it (outside, above, inside the hole).
      const nurbs_truth::TubePlace place{angle(rng), angle(rng)};
      const Vec c = place.point(R, a + rho - depth);
      ASSERT_NEAR(nurbs_truth::pointCircle(c, core), a + rho - depth, 1e-12);
      const Eigen::Isometry3d XA = randomRotation(rng);
      const Eigen::Isometry3d XB = placedIn(XA, scale * c);
      SCOPED_TRACE(::testing::Message() << "scale " << scale << " depth " << depth << " around " << place.around
                                        << " across " << place.across);
      const Vec away = XA.linear() * place.out();
      expectDepth(distance(torus, XA, ball, XB, opt), depth * scale, away, opt.tolerance);
      expectDepth(distance(torus, XA, sphere, XB, opt), depth * scale, away, opt.tolerance);
    }
  }
}

TEST(NurbsShallowDepth, BoxSunkIntoTheTubeTopGetsItsExactDepth) {
  const double R = 1, a = 0.25, half = 0.3;
  std::mt19937 rng(13);
  for (double scale : {1e-4, 1.0, 1e4}) {
    const NurbsModel torus({nurbs_fixtures::torusSurface(R * scale, a * scale)}, true);
    const Box box(scale * Vec(half, half, half));
    const DistanceOptions opt = atScale(scale);
    for (double depth : {1e-6, 1e-3, 0.05}) {
      // The box's bottom face centred over the tube's top, turned about the vertical.
      Eigen::Isometry3d X_AB = Eigen::Isometry3d::Identity();
      X_AB.translate(scale * Vec(0, R, a + half - depth));
      X_AB.rotate(Eigen::AngleAxisd(0.4, Vec::UnitZ()));
      const Eigen::Isometry3d XA = randomRotation(rng);
      SCOPED_TRACE(::testing::Message() << "scale " << scale << " depth " << depth);
      expectDepth(distance(torus, XA, box, XA * X_AB, opt), depth * scale, XA.linear() * Vec::UnitZ(), opt.tolerance);
    }
  }
}

// Random poses of the torus and random places around its tube, depths from 1e-7 to 0.35 (most of the ball's centre
// inside the tube): every bracket holds the truth and is certified. (A bound taken from a ball whose centre lay
// outside its solid once claimed more than the depth; the point queries' error once went uncounted.)
TEST(NurbsShallowDepth, RandomSunkBallsHoldTheTruth) {
  const double R = 1, a = 0.25, rho = 0.4;
  const NurbsModel torus({nurbs_fixtures::torusSurface(R, a)}, true);
  const NurbsModel ball({nurbs_fixtures::sphereSurface(rho)}, true);
  const Sphere sphere(rho);
  const Torus ring(R, a);  // the primitives' own pair too
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> angle(0, 2 * M_PI), u(-1, 1);
  DistanceOptions opt;
  opt.tolerance = 1e-9;
  for (double depth : {1e-7, 1e-4, 0.01, 0.1, 0.2, 0.3, 0.35}) {
    for (int k = 0; k < 8; ++k) {
      const nurbs_truth::TubePlace place{angle(rng), angle(rng)};
      Eigen::Isometry3d XA = randomRotation(rng);
      XA.translation() = Vec(u(rng), u(rng), u(rng));
      const Eigen::Isometry3d XB = placedIn(XA, place.point(R, a + rho - depth));
      SCOPED_TRACE(::testing::Message() << "depth " << depth << " around " << place.around << " across "
                                        << place.across);
      const std::pair<const Model*, const Model*> pairs[] = {{&torus, &ball}, {&torus, &sphere}, {&ring, &sphere}};
      for (const auto& [ma, mb] : pairs) {
        const DistanceResult r = distance(*ma, XA, *mb, XB, opt);
        EXPECT_EQ(r.status, Status::Certified) << r.method;
        EXPECT_LE(r.lowerBound, -depth + 1e-12);
        EXPECT_GE(r.upperBound, -depth - 1e-12);
      }
    }
  }
}

// Two tori, one shifted 0.1 along the other's axis through it: the translation separating them is 0.4 (up the
// axis, the tubes' circles 0.1 apart must get 0.5 apart) while no surface point is deeper than 0.1 in the other
// solid. Balls inscribed in both tubes at an escape's contact (here the supporting planes' escape along the
// models' axis, which stacks the tori touching along a circle), centred on its normal, prove what the surface
// points cannot: certified (the cone search alone left the bracket 7e-4 wide after 0.8 s).
TEST(NurbsShallowDepth, InscribedBallsBoundADeepTorusOverlap) {
  std::mt19937 rng(17);
  for (double scale : {1e-4, 1.0, 1e4}) {
    const NurbsModel torus({nurbs_fixtures::torusSurface(scale, 0.25 * scale)}, true);
    const DistanceOptions opt = atScale(scale);
    for (int k = 0; k < 2; ++k) {
      const Eigen::Isometry3d XA = randomRotation(rng);
      const Eigen::Isometry3d XB = placedIn(XA, Vec(0, 0, 0.1 * scale));
      SCOPED_TRACE(::testing::Message() << "scale " << scale << " pose " << k);
      const DistanceResult r = distance(torus, XA, torus, XB, opt);
      expectHolds(r, 0.4 * scale, opt.tolerance);
      EXPECT_EQ(r.status, Status::Certified);
    }
  }
}

// Rings stacked on one axis, the upper sunk into the lower by a sliver (1e-8 to 1e-6 of the size): the surfaces
// cross along two circles 1e-4 apart, and the pair search used to run its whole budget along them (2 s) before
// the full depth search answered with a bracket 1e-3 wide whose value said apart. Now a Newton end's point
// proved inside the other solid ends the search, and the escape up the axis meets the deepest point's depth.
// At the thinnest slivers the point query cannot prove that depth to the tolerance (its error bound grows as the
// squared distance's rounding over the distance), and the answer goes out bounded, the bracket a few tolerances.
TEST(NurbsShallowDepth, StackedRingsSunkBySliverAnswerFromTheEscape) {
  std::mt19937 rng(23);
  for (double scale : {1e-4, 1.0, 1e4}) {
    const NurbsModel torus({nurbs_fixtures::torusSurface(scale, 0.25 * scale)}, true);
    const DistanceOptions opt = atScale(scale);
    // Aligned (patch corners over patch corners: the case that ran the budget), turned about the axis, and in a
    // random pose.
    for (int pose = 0; pose < 3; ++pose) {
      for (double sliver : {1e-8, 3e-8, 1e-7, 1e-6}) {
        const double depth = sliver * scale;
        const Eigen::Isometry3d XA = pose == 2 ? randomRotation(rng) : Eigen::Isometry3d::Identity();
        Eigen::Isometry3d XB = placedIn(XA, Vec(0, 0, 0.5 * scale - depth));
        if (pose == 1) XB.rotate(Eigen::AngleAxisd(0.3, Vec::UnitZ()));
        SCOPED_TRACE(::testing::Message() << "scale " << scale << " sliver " << sliver << " pose " << pose);
        const DistanceResult r = distance(torus, XA, torus, XB, opt);
        expectHolds(r, depth, opt.tolerance);
        EXPECT_LT(r.upperBound, 0) << "the overlap is proved";
        EXPECT_LE(r.upperBound - r.lowerBound, 4 * opt.tolerance) << r.method;
        if (sliver >= 1e-7) {
          EXPECT_EQ(r.status, Status::Certified);
        }
      }
    }
  }
}

// A ball (radius 0.8, NURBS) resting in the ring's hole, sunk by g, its centre on the axis or δ off it: it
// touches the ring all round and leaves only to where its centre is a + ρ from the core circle all round, the
// top of the spindle the circle's (a + ρ)-neighbourhood makes over the axis: a distance √(δ² + Δz²), Δz about
// 3.3 g, deeper than any surface point is in the other solid (g). The ball's contacts all round bound the depth
// together and lead to the escape (ball_union.h): certified, where the full search left [−3.28 g, −g] (on the
// axis) after up to 0.9 s.
TEST(NurbsShallowDepth, BallSunkInTheRingsHoleLeavesUpTheAxis) {
  std::mt19937 rng(29);
  const double R = 1, a = 0.25, rho = 0.8;
  const double top = std::sqrt((a + rho) * (a + rho) - R * R);  // the spindle's top over the axis
  for (double scale : {1e-4, 1.0, 1e4}) {
    const NurbsModel torus({nurbs_fixtures::torusSurface(R * scale, a * scale)}, true);
    const NurbsModel ball({nurbs_fixtures::sphereSurface(rho * scale)}, true);
    const Sphere sphere(rho * scale);  // (through its exact NURBS form: its point queries took 5–40 s here)
    const Torus ring(R * scale, a * scale);  // with the sphere: the primitives' own escape search stayed bounded
    const DistanceOptions opt = atScale(scale);
    for (const auto& [g, off] : {std::pair{1e-8, 0.0}, {1e-6, 0.0}, {1e-4, 0.0}, {1e-2, 0.0}, {1e-4, 1e-9},
                                 {1e-4, 1e-6}, {1e-4, 1e-4}}) {
      const double height = std::sqrt((a + rho - g) * (a + rho - g) - R * R);
      const double depth = scale * std::hypot(off, top - height);
      const Eigen::Isometry3d XA = randomRotation(rng);
      const Eigen::Isometry3d XB = placedIn(XA, Vec(scale * off, 0, scale * height));
      SCOPED_TRACE(::testing::Message() << "scale " << scale << " sunk " << g << " off the axis " << off);
      const Vec way = XA.linear() * Vec(-off, 0, top - height).normalized();
      // The primitives' routes at one scale (they take the NURBS ball's route, a few times over).
      const std::pair<const Model*, const Model*> pairs[] = {{&torus, &ball}, {&torus, &sphere}, {&ring, &sphere}};
      for (const auto& [ma, mb] : pairs) {
        if (mb != &ball && scale != 1.0) continue;
        const DistanceResult r = distance(*ma, XA, *mb, XB, opt);
        expectHolds(r, depth, opt.tolerance);
        EXPECT_EQ(r.status, Status::Certified) << r.method;
        EXPECT_GT(r.normal.dot(way), 1 - 1e-6) << "to the spindle's top";
      }
    }
  }
}

// A sphere primitive sunk into the NURBS torus's tube leaves along the contact normal: one point query at the
// moved centre proves it out, and the bracket closes on the centre's depth (~10 µs; through the NURBS–convex
// route 0.7–19 ms). In the ring's hole that way is blocked, and the answer comes from the exact NURBS forms.
TEST(NurbsShallowDepth, SphereSunkIntoTheTubeLeavesAlongTheNormal) {
  const double R = 1, a = 0.25, rho = 0.4;
  const NurbsModel torus({nurbs_fixtures::torusSurface(R, a)}, true);
  const Sphere sphere(rho);
  const DistanceOptions opt = atScale(1);
  for (double depth : {1e-9, 1e-5, 0.1, 0.3}) {
    const nurbs_truth::TubePlace place{0.7, 1.1};
    const Eigen::Isometry3d XB = nurbs_truth::pose(place.point(R, a + rho - depth));
    const DistanceResult r = distance(torus, Eigen::Isometry3d::Identity(), sphere, XB, opt);
    SCOPED_TRACE(::testing::Message() << "depth " << depth);
    expectDepth(r, depth, place.out(), opt.tolerance);
    EXPECT_STREQ(r.method, "sphere-escape-along-normal");
  }
  const Sphere big(0.8);
  const double height = std::sqrt((a + 0.8 - 1e-4) * (a + 0.8 - 1e-4) - R * R);
  const DistanceResult hole =
      distance(torus, Eigen::Isometry3d::Identity(), big, nurbs_truth::pose(Vec(0, 0, height)), opt);
  EXPECT_EQ(hole.status, Status::Certified);
  EXPECT_STRNE(hole.method, "sphere-escape-along-normal") << "the way along the contact normal is blocked";
}

}  // namespace
}  // namespace unidist
