// NURBS – point cloud (core/src/pairs/nurbs_cloud.cpp) against the brute-force oracle: every cloud point's own
// NURBS point query (signed for a solid), the least of them. Value, bounds and status at random poses: clouds
// apart, touching, partly inside, wholly inside, around the model; an open patch; scales 1e-4 and 1e4; one point;
// both argument orders; a coarse and a fine tolerance.
#include "core/nurbs_fixtures.h"
#include "unidist/distance.h"
#include "unidist/point_cloud.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace {

using unidist::DistanceOptions;
using unidist::DistanceResult;
using unidist::NurbsModel;
using unidist::PointCloud;
using Points = std::vector<Eigen::Vector3d>;

struct Truth {
  double value;  // min over the points of the (signed) distance
  double error;  // the point queries' error bound
};

/// The oracle: every point queried, in the NURBS model's frame.
Truth oracle(const NurbsModel& nurbs, const Eigen::Isometry3d& X_WA, const Points& points, const Eigen::Isometry3d& X_WB) {
  Truth t{std::numeric_limits<double>::infinity(), 0};
  const Eigen::Isometry3d X_AB = X_WA.inverse() * X_WB;
  for (const Eigen::Vector3d& p : points) {
    const unidist::SurfacePoint s = nurbs.closestPoint(X_AB * p);
    t.value = std::min(t.value, s.signedDistance);
    t.error = std::max(t.error, s.error);
  }
  return t;
}

Eigen::Isometry3d randomPose(std::mt19937& rng, const Eigen::Vector3d& translation) {
  std::normal_distribution<double> g;
  const Eigen::Quaterniond q(g(rng), g(rng), g(rng), g(rng));
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = q.normalized().toRotationMatrix();
  X.translation() = translation;
  return X;
}

/// `count` points uniform in the ball (centre, radius).
Points blob(std::mt19937& rng, int count, const Eigen::Vector3d& centre, double radius) {
  std::uniform_real_distribution<double> u(-1, 1);
  Points p;
  while (static_cast<int>(p.size()) < count) {
    const Eigen::Vector3d x(u(rng), u(rng), u(rng));
    if (x.norm() <= 1) p.push_back(centre + radius * x);
  }
  return p;
}

/// `count` points on the sphere (centre, radius).
Points shell(std::mt19937& rng, int count, const Eigen::Vector3d& centre, double radius) {
  std::normal_distribution<double> g;
  Points p;
  for (int i = 0; i < count; ++i) p.push_back(centre + radius * Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized());
  return p;
}

/// Runs both argument orders and checks them against the oracle; returns the NURBS-first answer.
DistanceResult expectMatchesOracle(const NurbsModel& nurbs, const Eigen::Isometry3d& X_WA, const Points& points,
                                   const Eigen::Isometry3d& X_WB, double tolerance, const std::string& what) {
  const PointCloud cloud(points);
  DistanceOptions o;
  o.tolerance = tolerance;
  const Truth truth = oracle(nurbs, X_WA, points, X_WB);
  const double size = std::max(nurbs.localBounds().diagonal(), cloud.localBounds().diagonal());
  const double slack = truth.error + 1e-12 * size;
  const DistanceResult r = unidist::distance(nurbs, X_WA, cloud, X_WB, o);
  const DistanceResult s = unidist::distance(cloud, X_WB, nurbs, X_WA, o);
  for (const DistanceResult* x : {&r, &s}) {
    SCOPED_TRACE(what + (x == &r ? " (NURBS first)" : " (cloud first)"));
    EXPECT_STREQ(x->method, "nurbs-cloud-bvh");
    EXPECT_LE(x->lowerBound, truth.value + slack);
    EXPECT_GE(x->upperBound, truth.value - slack);
    EXPECT_LE(x->lowerBound, x->distance);
    EXPECT_LE(x->distance, x->upperBound);
    EXPECT_EQ(x->status, unidist::Status::Certified) << "bounds [" << x->lowerBound << ", " << x->upperBound << "]";
    EXPECT_LE(x->upperBound - x->lowerBound, tolerance + slack);
    EXPECT_NEAR(x->distance, truth.value, tolerance + slack);
    // point_b − point_a = distance · normal; the cloud's witness is one of its points.
    EXPECT_LT((x->pointB - x->pointA - x->distance * x->normal).norm(), 1e-9 * size);
    EXPECT_NEAR(x->normal.norm(), 1.0, 1e-12);
  }
  EXPECT_EQ(r.distance, s.distance);
  EXPECT_EQ(r.pointA, s.pointB);
  EXPECT_EQ(r.normal, -s.normal);
  const Eigen::Vector3d cloudPoint_B = X_WB.inverse() * r.pointB;
  double nearestSq = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& p : points) nearestSq = std::min(nearestSq, (p - cloudPoint_B).squaredNorm());
  EXPECT_LT(std::sqrt(nearestSq), 1e-12 * size) << what;
  return r;
}

/// The cloud moved (in the world) so that its closest point lands on the surface: by −distance along the normal.
Eigen::Isometry3d touchingPose(const NurbsModel& nurbs, const Points& points, const Eigen::Isometry3d& X_WB) {
  const PointCloud cloud(points);
  const DistanceResult r = unidist::distance(nurbs, Eigen::Isometry3d::Identity(), cloud, X_WB);
  Eigen::Isometry3d moved = X_WB;
  moved.pretranslate(-r.distance * r.normal);
  return moved;
}

struct Fixture {
  std::string name;
  std::unique_ptr<NurbsModel> model;
  double outer;  // radius of a ball around the origin holding the model
};

std::vector<Fixture> solids(double scale) {
  std::vector<Fixture> f;
  f.push_back({"torus", std::make_unique<NurbsModel>(std::vector{nurbs_fixtures::torusSurface(1, 0.25, scale)}, true),
               1.25 * scale});
  f.push_back({"sphere", std::make_unique<NurbsModel>(std::vector{nurbs_fixtures::sphereSurface(scale)}, true), scale});
  return f;
}

Eigen::Vector3d randomDirection(std::mt19937& rng) {
  std::normal_distribution<double> g;
  return Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
}

/// Every kind of placement for one solid at one scale and tolerance (relative to the size).
void placementsOfSolid(const Fixture& f, double scale, double relativeTolerance, std::mt19937& rng, int points) {
  const double size = f.model->localBounds().diagonal();
  const double tol = relativeTolerance * size;
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  const std::string at = f.name + " scale " + std::to_string(scale) + " tol " + std::to_string(relativeTolerance);
  // Apart, at random poses.
  const Points apart = blob(rng, points, Eigen::Vector3d::Zero(), 0.3 * scale);
  const Eigen::Isometry3d farPose = randomPose(rng, (f.outer + 0.5 * scale) * randomDirection(rng));
  const DistanceResult r = expectMatchesOracle(*f.model, I, apart, farPose, tol, at + ": apart");
  EXPECT_GT(r.distance, 0);
  // Touching: the closest point on the surface (within rounding).
  const Eigen::Isometry3d touch = touchingPose(*f.model, apart, farPose);
  const DistanceResult t = expectMatchesOracle(*f.model, I, apart, touch, tol, at + ": touching");
  EXPECT_LT(std::abs(t.distance), 1e-12 * size);
  // Partly inside: a blob around a surface point (the answer is minus the deepest point's depth).
  const Eigen::Vector3d onSurface = f.model->closestPoint(f.outer * randomDirection(rng)).point;
  const DistanceResult p = expectMatchesOracle(*f.model, I, blob(rng, points, Eigen::Vector3d::Zero(), 0.2 * scale),
                                               randomPose(rng, onSurface), tol, at + ": partly inside");
  EXPECT_LT(p.distance, 0);
  // A shell of the cloud around the whole model (the cloud's ball holds the model, no point inside).
  expectMatchesOracle(*f.model, I, shell(rng, points, Eigen::Vector3d::Zero(), 1.6 * f.outer),
                      randomPose(rng, 0.1 * scale * randomDirection(rng)), tol, at + ": around");
}

TEST(NurbsCloud, SolidsAtRandomPosesMatchTheOracle) {
  std::mt19937 rng(7);
  for (const double relativeTolerance : {1e-3, 1e-10}) {
    const std::vector<Fixture> fixtures = solids(1);
    for (const Fixture& f : fixtures) placementsOfSolid(f, 1, relativeTolerance, rng, 600);
  }
}

TEST(NurbsCloud, ExtremeScalesMatchTheOracle) {
  std::mt19937 rng(11);
  for (const double scale : {1e-4, 1e4}) {
    const std::vector<Fixture> fixtures = solids(scale);
    for (const Fixture& f : fixtures) placementsOfSolid(f, scale, 1e-10, rng, 300);
  }
}

TEST(NurbsCloud, CloudWhollyInsideTheSphere) {
  std::mt19937 rng(3);
  const NurbsModel sphere({nurbs_fixtures::sphereSurface(1)}, true);
  for (const double relativeTolerance : {1e-3, 1e-10})
    for (int k = 0; k < 3; ++k) {
      const Points inside = blob(rng, 2000, Eigen::Vector3d::Zero(), 0.4);
      const Eigen::Isometry3d pose = randomPose(rng, 0.3 * randomDirection(rng));
      const DistanceResult r = expectMatchesOracle(sphere, Eigen::Isometry3d::Identity(), inside, pose,
                                                   relativeTolerance * sphere.localBounds().diagonal(), "inside");
      EXPECT_LT(r.distance, -0.2);
    }
}

TEST(NurbsCloud, CloudInsideTheTorusTube) {
  std::mt19937 rng(5);
  const NurbsModel torus({nurbs_fixtures::torusSurface(1, 0.25)}, true);
  // Points along the core circle, within 0.15 of it: wholly inside the tube.
  Points core;
  std::uniform_real_distribution<double> angle(0, 2 * M_PI);
  for (const Eigen::Vector3d& offset : blob(rng, 1500, Eigen::Vector3d::Zero(), 0.15)) {
    const double a = angle(rng);
    core.push_back(Eigen::Vector3d(std::cos(a), std::sin(a), 0) + offset);
  }
  const DistanceResult r =
      expectMatchesOracle(torus, Eigen::Isometry3d::Identity(), core, Eigen::Isometry3d::Identity(), 1e-9, "tube");
  EXPECT_LT(r.distance, -0.1);
}

TEST(NurbsCloud, OpenPatchIsUnsigned) {
  std::mt19937 rng(13);
  const NurbsModel wavy({nurbs_fixtures::wavySurface()}, false);
  const double size = wavy.localBounds().diagonal();
  for (const double relativeTolerance : {1e-3, 1e-10})
    for (int k = 0; k < 4; ++k) {
      // Blobs across the sheet (distance 0 where points lie on both sides) and above it.
      std::uniform_real_distribution<double> u(-0.8, 0.8);
      const Eigen::Vector3d centre(u(rng), u(rng), k < 2 ? 0.0 : 0.8);
      const DistanceResult r =
          expectMatchesOracle(wavy, Eigen::Isometry3d::Identity(), blob(rng, 500, Eigen::Vector3d::Zero(), 0.25),
                              randomPose(rng, centre), relativeTolerance * size, "wavy");
      EXPECT_GE(r.lowerBound, 0);
    }
}

TEST(NurbsCloud, OnePointCloud) {
  const NurbsModel torus({nurbs_fixtures::torusSurface(1, 0.25)}, true);
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(3, 0.5, 0.2), Eigen::Vector3d(1.1, 0, 0.05),
                                   Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 1.25, 0)})
    expectMatchesOracle(torus, I, {p}, I, 1e-9, "one point");
}

}  // namespace
