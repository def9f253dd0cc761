// Level of detail (Model::atDetail, QueryOptions::detailA/B): the stand-ins' proved deviations hold both ways
// against dense samples of the exact models, the queries' widened bounds hold the exact answers, and levels are
// built once, shared between threads, and refused when malformed.
#include "nurbs_fixtures.h"
#include "unidist/contacts.h"
#include "unidist/distance.h"
#include "unidist/mesh.h"
#include "unidist/point_cloud.h"
#include "unidist/primitives.h"
#include "unidist/tracker.h"

#include <gtest/gtest.h>

#include <random>
#include <thread>

namespace {

using unidist::Model;
using unidist::NurbsModel;
using unidist::StandIn;
using unidist::TriangleMesh;

struct TessellationCase {
  const char* name;
  unidist::NurbsSurface (*surface)();
  bool solid;
};

unidist::NurbsSurface sphere() { return nurbs_fixtures::sphereSurface(1.0); }
unidist::NurbsSurface torus() { return nurbs_fixtures::torusSurface(1.0, 0.25); }
unidist::NurbsSurface wavy() { return nurbs_fixtures::wavySurface(); }
unidist::NurbsSurface cylinder() { return nurbs_fixtures::cylinderSurface(0.5, 1.0); }

const TessellationCase kCases[] = {
    {"sphere", sphere, true}, {"torus", torus, true}, {"wavy", wavy, false}, {"cylinder", cylinder, false}};

/// Largest distance from dense surface samples to the stand-in, and from samples of the stand-in's triangles
/// to the exact surface: the two halves of the Hausdorff distance, measured.
double measuredHausdorff(const NurbsModel& exact, const TriangleMesh& mesh) {
  double worst = 0;
  for (const unidist::NurbsSurface& s : exact.surfaces())
    for (int i = 0; i <= 90; ++i)
      for (int j = 0; j <= 90; ++j) {
        const double u = s.uMin() + (s.uMax() - s.uMin()) * i / 90.0, v = s.vMin() + (s.vMax() - s.vMin()) * j / 90.0;
        worst = std::max(worst, std::abs(mesh.closestPoint(s.evaluate(u, v)).signedDistance));
      }
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0, 1);
  const std::size_t triangles = mesh.triangles().size(), samples = std::max<std::size_t>(4 * triangles, 8000);
  for (std::size_t k = 0; k < std::min<std::size_t>(samples, 20000); ++k) {
    const std::size_t t = samples > 20000 ? rng() % triangles : k % triangles;
    double b1 = unit(rng), b2 = unit(rng);
    if (b1 + b2 > 1) b1 = 1 - b1, b2 = 1 - b2;
    const auto& tri = mesh.triangles()[t];
    const Eigen::Vector3d p = (1 - b1 - b2) * mesh.vertices()[tri[0]] + b1 * mesh.vertices()[tri[1]] +
                              b2 * mesh.vertices()[tri[2]];
    worst = std::max(worst, std::abs(exact.closestPoint(p).signedDistance));
    }
  return worst;
}

TEST(LevelOfDetail, NurbsTessellationDeviationHoldsBothWays) {
  for (const TessellationCase& c : kCases) {
    const NurbsModel exact({c.surface()}, c.solid);
    std::size_t lastTriangles = 0;
    for (double level : {0.1, 0.01, 1e-3}) {
      SCOPED_TRACE(std::string(c.name) + " at " + std::to_string(level));
      const StandIn s = exact.atDetail(level);
      ASSERT_NE(s.model, &exact);
      const auto* mesh = dynamic_cast<const TriangleMesh*>(s.model);
      ASSERT_NE(mesh, nullptr);
      EXPECT_GT(s.deviation, 0);
      EXPECT_LE(s.deviation, level);
      EXPECT_EQ(mesh->isSolid(), c.solid);
      const double measured = measuredHausdorff(exact, *mesh);
      EXPECT_LE(measured, s.deviation + 1e-12);
      // Not a vacuous bound: the proof is within a small factor of what the samples see.
      EXPECT_GT(measured, s.deviation / 20);
      EXPECT_GT(static_cast<std::size_t>(static_cast<int>(mesh->triangles().size())), lastTriangles);
      lastTriangles = static_cast<std::size_t>(static_cast<int>(mesh->triangles().size()));
      std::printf("%s level %.0e: %d triangles, proved %.3g, measured %.3g\n", c.name, level, static_cast<int>(mesh->triangles().size()),
                  s.deviation, measured);
    }
  }
}

TEST(LevelOfDetail, LevelsAreBuiltOnceAndShared) {
  const NurbsModel exact({torus()}, true);
  EXPECT_EQ(exact.atDetail(0).model, &exact);
  ASSERT_EQ(exact.structures().size(), 3u);  // patch tree, levels, point query cells
  EXPECT_FALSE(exact.structures()[1].built);  // no level asked yet
  std::vector<const Model*> seen(4);
  std::vector<std::thread> threads;
  for (std::size_t k = 0; k < seen.size(); ++k)
    threads.emplace_back([&, k] { seen[k] = exact.atDetail(0.02).model; });
  for (std::thread& t : threads) t.join();
  for (const Model* m : seen) EXPECT_EQ(m, seen[0]);
  EXPECT_EQ(exact.atDetail(0.02).model, seen[0]);
  const auto structures = exact.structures();
  ASSERT_EQ(structures.size(), 3u);
  EXPECT_EQ(structures[1].name, "level-of-detail");
  EXPECT_TRUE(structures[1].built);
  EXPECT_GT(structures[1].bytes, 0u);
}

TEST(LevelOfDetail, ModelsWithoutCoarserFormAnswerThemselves) {
  const unidist::Sphere ball(1.0);
  EXPECT_EQ(ball.atDetail(0.1).model, &ball);
  EXPECT_EQ(ball.atDetail(0.1).deviation, 0);
  const TriangleMesh tri({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}});
  EXPECT_EQ(tri.atDetail(0.1).model, &tri);
  // Finer than the welding of a solid's seams (1e-9 × size): the exact model.
  const NurbsModel exact({sphere()}, true);
  EXPECT_EQ(exact.atDetail(1e-12).model, &exact);
}

TEST(LevelOfDetail, MalformedLevelsAreRefused) {
  const NurbsModel exact({sphere()}, true);
  for (double bad : {-1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    EXPECT_THROW(exact.atDetail(bad), unidist::InputError);
    unidist::DistanceOptions o;
    o.detailB = bad;
    EXPECT_THROW(unidist::distance(exact, Eigen::Isometry3d::Identity(), exact, Eigen::Isometry3d::Identity(), o),
                 unidist::InputError);
    unidist::ContactOptions co;
    co.detailA = bad;
    EXPECT_THROW(unidist::contacts(exact, Eigen::Isometry3d::Identity(), exact, Eigen::Isometry3d::Identity(), co),
                 unidist::InputError);
  }
}

TEST(LevelOfDetail, CloudDecimationKeepsEveryPointWithinItsDeviation) {
  std::mt19937 rng(3);
  std::normal_distribution<double> g(0, 1);
  std::vector<Eigen::Vector3d> points, normals;
  for (int k = 0; k < 20000; ++k) {
    const Eigen::Vector3d p = Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
    points.push_back(p);
    normals.push_back(p);
  }
  const unidist::PointCloud cloud(points, normals);
  for (double level : {0.3, 0.1, 0.03}) {
    const StandIn s = cloud.atDetail(level);
    const auto* coarse = dynamic_cast<const unidist::PointCloud*>(s.model);
    ASSERT_NE(coarse, nullptr);
    ASSERT_NE(coarse, &cloud);
    EXPECT_LT(coarse->points().size(), points.size());
    EXPECT_EQ(coarse->normals().size(), coarse->points().size());
    EXPECT_LE(s.deviation, level);
    double worst = 0;
    for (const Eigen::Vector3d& p : points) worst = std::max(worst, coarse->closestPoint(p).signedDistance);
    EXPECT_LE(worst, s.deviation);
    EXPECT_GT(worst, s.deviation / 2);  // the deviation is the farthest dropped point from its kept one
  }
  // A level finer than every spacing drops nothing: the cloud itself.
  EXPECT_EQ(cloud.atDetail(1e-9).model, &cloud);
}

TEST(LevelOfDetail, DistanceBoundsHoldTheExactAnswer) {
  const NurbsModel ball({sphere()}, true);  // radius 1
  const unidist::Sphere probe(0.5);
  const unidist::Box slab(Eigen::Vector3d(4, 4, 0.5));  // half extents
  struct Pose {
    Eigen::Vector3d where;
    const Model* other;
    double truth;
  };
  const Pose poses[] = {{{1.8, 0.2, -0.1}, &probe, Eigen::Vector3d(1.8, 0.2, -0.1).norm() - 1.5},
                        {{0.3, 0.9, 0.4}, &probe, Eigen::Vector3d(0.3, 0.9, 0.4).norm() - 1.5},
                        {{0, 0, 1.3}, &slab, -0.2},   // the slab's top face 0.2 into the ball
                        {{0, 0, 1.6}, &slab, 0.1}};
  for (double level : {0.05, 1e-3}) {
    for (const Pose& p : poses) {
      SCOPED_TRACE(::testing::Message() << "level " << level << " at " << p.where.transpose());
      Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
      X.translation() = p.where;
      unidist::DistanceOptions o;
      o.detailA = level;
      o.tolerance = 1e-2;
      const unidist::DistanceResult r = unidist::distance(ball, Eigen::Isometry3d::Identity(), *p.other, X, o);
      EXPECT_LE(r.lowerBound, p.truth);
      EXPECT_GE(r.upperBound, p.truth);
      const double deviation = ball.atDetail(level).deviation;
      EXPECT_GE(r.errorBound(), 2 * deviation * (1 - 1e-12));  // the stand-in's deviation is in the bounds
      // Certified exactly when the bounds meet the tolerance, the deviation included.
      EXPECT_EQ(r.status == unidist::Status::Certified, r.errorBound() <= o.tolerance);
      EXPECT_NEAR(r.distance, p.truth, 2 * deviation + o.tolerance);
    }
  }
}

TEST(LevelOfDetail, ContactsAreTheStandInsAndOverlapVerdictsStayHonest) {
  const NurbsModel ball({sphere()}, true);
  const unidist::Sphere probe(0.5);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(1.45, 0, 0);  // 0.05 into the ball
  unidist::ContactOptions co;
  co.detailA = 0.01;
  const auto found = unidist::contacts(ball, Eigen::Isometry3d::Identity(), probe, X, co);
  ASSERT_FALSE(found.empty());
  EXPECT_NEAR(found.front().distance, -0.05, 0.02 + 1e-9);
  // An overlap verdict within the deviation of touching is not claimed as proved.
  unidist::DistanceOptions o;
  o.compute = unidist::Compute::Overlap;
  o.detailA = 0.01;
  X.translation() = Eigen::Vector3d(1.5 + 1e-4, 0, 0);
  const unidist::DistanceResult near = unidist::distance(ball, Eigen::Isometry3d::Identity(), probe, X, o);
  EXPECT_LE(near.lowerBound, 1e-4);
  EXPECT_GE(near.upperBound, 1e-4);
  EXPECT_EQ(near.status, unidist::Status::Bounded);
  X.translation() = Eigen::Vector3d(1.7, 0, 0);
  const unidist::DistanceResult apart = unidist::distance(ball, Eigen::Isometry3d::Identity(), probe, X, o);
  EXPECT_GT(apart.lowerBound, 0);
  EXPECT_EQ(apart.status, unidist::Status::Certified);
}

// The tracker follows the stand-in: a NURBS ball tracked at a level of detail against a probe stays within the
// deviation (and the tracker's tolerance) of the exact gap along a trajectory.
TEST(LevelOfDetail, TrackerFollowsTheStandIn) {
  const auto ball = std::make_shared<NurbsModel>(std::vector<unidist::NurbsSurface>{sphere()}, true);
  const auto probe = std::make_shared<unidist::Sphere>(0.25);
  unidist::TrackerOptions o;
  o.detailA = 5e-3;
  o.cutoff = 0.2;
  o.globalPass = unidist::GlobalPassMode::Inline;
  unidist::Tracker tracker(ball, probe, o);
  const unidist::StandIn standIn = ball->atDetail(5e-3);
  const double deviation = standIn.deviation;
  double offExact = 0;  // how far the tracked points stray from the exact sphere: they are the stand-in's
  for (int k = 0; k < 200; ++k) {
    const double angle = 0.01 * k, gap = 0.1 + 0.05 * std::sin(0.05 * k);
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation() = (1.25 + gap) * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0.3).normalized();
    const unidist::TrackerUpdate& u = tracker.update(Eigen::Isometry3d::Identity(), X);
    ASSERT_EQ(u.minima, 1) << "update " << k;
    EXPECT_NEAR(u.deepest, gap, deviation + 1e-5) << "update " << k;
    const Eigen::Vector3d pA = tracker.minima().front().pointA;
    EXPECT_LT(std::abs(standIn.model->closestPoint(pA).signedDistance), 1e-9);
    offExact = std::max(offExact, std::abs(pA.norm() - 1.0));
  }
  EXPECT_GT(offExact, 1e-2 * deviation);
}

}  // namespace
