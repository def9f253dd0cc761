// The dial's switches (unidist/query_options.h, DistanceOptions::compute): what each kind of query computes,
// that the cheaper kinds skip the penetration solve, the relative tolerance's guarantee, and how two dials
// combine for a pair.
#include "core/mesh_fixtures.h"
#include "core/nurbs_fixtures.h"
#include "bench/nurbs_truth.h"
#include "core/query_helpers.h"
#include "unidist/distance.h"
#include "unidist/mesh.h"
#include "unidist/nurbs.h"
#include "unidist/primitives.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;
using unidist::Compute;
using unidist::DistanceOptions;
using unidist::Status;

Isometry3d at(const Vector3d& t) { return query_test::translation(t); }

/// Two interlocking-capable torus meshes (R = 1, r = 0.25): non-convex solids, whose depth is a real search.
struct TorusPair : ::testing::Test {
  unidist::TriangleMesh a = meshfix::makeMesh(meshfix::torus(1.0, 0.25, 48, 16));
  unidist::TriangleMesh b = meshfix::makeMesh(meshfix::torus(1.0, 0.25, 48, 16));
  const Isometry3d X_WA = Isometry3d::Identity();
  // Side by side, tubes 0.3 apart (centres 2.8 apart along x): the closest points are on the outer equators, at a
  // vertex of each mesh (u = 0 and u = π, v = 0), where the facets lie inside the exact tori: the gap is exact.
  const Isometry3d apart = at(Vector3d(2.8, 0, 0));
  const double gap = 0.3;
  // Tubes crossing: B's inner equator 0.3 inside A's outer one.
  const Isometry3d crossing = at(Vector3d(1.9, 0, 0));

  DistanceOptions kind(Compute c) const {
    DistanceOptions o;
    o.compute = c;
    return o;
  }
};

TEST_F(TorusPair, OverlapDecidesBothWaysAndProvesItsVerdict) {
  const auto sep = unidist::distance(a, X_WA, b, apart, kind(Compute::Overlap));
  EXPECT_FALSE(sep.overlapping());
  EXPECT_GT(sep.lowerBound, 0);
  EXPECT_EQ(sep.status, Status::Certified);

  const auto hit = unidist::distance(a, X_WA, b, crossing, kind(Compute::Overlap));
  EXPECT_TRUE(hit.overlapping());
  EXPECT_LE(hit.upperBound, 0);
  EXPECT_EQ(hit.status, Status::Certified);
  EXPECT_STREQ(hit.method, "overlap-verdict");  // proved by the crossing surfaces; no depth was measured
}

TEST_F(TorusPair, SeparationMeasuresGapsButNotDepths) {
  const auto full = unidist::distance(a, X_WA, b, apart);
  const auto sep = unidist::distance(a, X_WA, b, apart, kind(Compute::Separation));
  EXPECT_NEAR(full.distance, gap, 1e-8);
  EXPECT_NEAR(sep.distance, gap, 1e-8);
  EXPECT_EQ(sep.status, Status::Certified);

  const auto depth = unidist::distance(a, X_WA, b, crossing);
  ASSERT_LT(depth.distance, 0);
  EXPECT_STRNE(depth.method, "overlap-verdict");
  const auto verdict = unidist::distance(a, X_WA, b, crossing, kind(Compute::Separation));
  EXPECT_LE(verdict.upperBound, 0);
  EXPECT_STREQ(verdict.method, "overlap-verdict");
  // What is proved stays true: the verdict's bounds hold the measured depth.
  EXPECT_LE(verdict.lowerBound, depth.distance);
}

TEST(Overlap, TouchingWithinToleranceCountsAsOverlapping) {
  const unidist::Sphere s(1.0);
  const auto r = unidist::distance(s, Isometry3d::Identity(), s, at(Vector3d(2.0 + 1e-13, 0, 0)),
                                   [] { DistanceOptions o; o.compute = Compute::Overlap; o.tolerance = 1e-9; return o; }());
  EXPECT_LE(r.lowerBound, 1e-13);
  EXPECT_GE(r.upperBound, 1e-13);
  EXPECT_LE(r.errorBound(), 1e-9);
}

TEST(Overlap, NurbsSphereAgainstBoxBothWays) {
  const unidist::NurbsModel ball({nurbs_fixtures::sphereSurface(1.0)}, true);
  const unidist::Box box(Vector3d(0.5, 0.5, 0.5));
  DistanceOptions o;
  o.compute = Compute::Overlap;
  for (double gap : {0.25, 1e-3, -1e-3, -0.25}) {
    const auto r = unidist::distance(ball, Isometry3d::Identity(), box, at(Vector3d(1.5 + gap, 0, 0)), o);
    EXPECT_EQ(r.overlapping(), gap < 0) << gap;
    EXPECT_EQ(r.status, Status::Certified) << gap;
    EXPECT_TRUE(gap < 0 ? r.upperBound <= 0 : r.lowerBound > 0) << gap;
  }
}

// Crossing NURBS tori: the verdict comes from a point of one inside the other (corners, a grid on every patch,
// then a short field search), not from measuring the depth (before: the translation-depth search, 0.4-0.8 s per
// pose). Poses 0.3 apart and 1e-6 apart stay proved apart.
TEST(Overlap, CrossingNurbsToriAreDecidedByAPointInside) {
  const unidist::NurbsModel torus({nurbs_fixtures::torusSurface(1, 0.25)}, true);
  const auto pose = [](double x, double y, double z, double qw, double qx, double qy, double qz) {
    Isometry3d X = Isometry3d::Identity();
    X.linear() = Eigen::Quaterniond(qw, qx, qy, qz).normalized().toRotationMatrix();
    X.translation() = Vector3d(x, y, z);
    return X;
  };
  DistanceOptions o;
  o.compute = Compute::Overlap;
  for (const Isometry3d& X : {pose(1.666, 0.879, 0.134, 0.402, 0.784, 0.469, 0.065),
                              pose(-1.524, 0.487, 0.629, 0.433, 0.733, 0.179, -0.493),
                              pose(0.825, -0.387, 1.080, 0.668, -0.293, 0.682, -0.049),
                              pose(-1.756, -0.077, 0.394, 0.852, -0.238, -0.443, -0.147), at(Vector3d(1.9, 0, 0))}) {
    // Truth: solid tori of tube radius 0.25 overlap where their core circles come closer than 0.5.
    const nurbs_truth::Circle core{Vector3d::Zero(), Vector3d::UnitZ(), 1.0};
    ASSERT_LT(nurbs_truth::circleCircle(core, {X.translation(), X.linear() * Vector3d::UnitZ(), 1.0}), 0.5);
    const auto r = unidist::distance(torus, Isometry3d::Identity(), torus, X, o);
    EXPECT_LE(r.upperBound, 0);
    EXPECT_EQ(r.status, Status::Certified);
    EXPECT_STREQ(r.method, "overlap-verdict");
  }
  for (double gap : {0.3, 1e-6}) {
    const auto r = unidist::distance(torus, Isometry3d::Identity(), torus, at(Vector3d(2.5 + gap, 0, 0)), o);
    EXPECT_GT(r.lowerBound, 0) << gap;
    EXPECT_EQ(r.status, Status::Certified) << gap;
  }
}

TEST(RelativeTolerance, FarPairsAreCoarserButWithinTheirGuarantee) {
  const unidist::NurbsModel ball({nurbs_fixtures::sphereSurface(1.0)}, true);
  const unidist::Sphere probe(0.5);
  const double truth = 100.0 - 1.0 - 0.5;
  DistanceOptions o;
  o.tolerance = 1e-12;
  o.relativeTolerance = 1e-3;
  // The point query of a sphere probe is exact; a NURBS probe shows the trade: answer within 1e-3 of 98.5.
  const unidist::NurbsModel probeNurbs({nurbs_fixtures::sphereSurface(0.5)}, true);
  const auto coarse = unidist::distance(ball, Isometry3d::Identity(), probeNurbs, at(Vector3d(100, 0, 0)), o);
  EXPECT_NEAR(coarse.distance, truth, 1e-3 * truth);
  EXPECT_LE(coarse.lowerBound, truth);
  EXPECT_GE(coarse.upperBound, truth);
  EXPECT_LE(coarse.errorBound(), 1e-3 * truth);
  const auto exact = unidist::distance(ball, Isometry3d::Identity(), probe, at(Vector3d(100, 0, 0)), o);
  EXPECT_NEAR(exact.distance, truth, 1e-3 * truth);
  // Touching pairs get no relative slack: the bounding spheres meet, so the absolute tolerance rules.
  const auto near = unidist::distance(ball, Isometry3d::Identity(), probeNurbs, at(Vector3d(1.5 + 1e-6, 0, 0)), o);
  EXPECT_NEAR(near.distance, 1e-6, 1e-10);
}

TEST(QueryOptions, BadSettingsAreRefusedByName) {
  const unidist::Sphere s(1.0);
  for (double rel : {-1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    DistanceOptions o;
    o.relativeTolerance = rel;
    try {
      unidist::distance(s, Isometry3d::Identity(), s, at(Vector3d(3, 0, 0)), o);
      ADD_FAILURE() << rel;
    } catch (const unidist::InputError& e) {
      EXPECT_NE(std::string(e.what()).find("relative tolerance"), std::string::npos);
    }
  }
}

TEST(QueryOptions, ThePairUsesTheStricterDial) {
  unidist::QueryOptions a, b;
  EXPECT_LT(unidist::stricter(a, b).tolerance, 0);  // both default: the default
  a.tolerance = 1e-3;
  EXPECT_EQ(unidist::stricter(a, b).tolerance, 1e-3);
  EXPECT_EQ(unidist::stricter(b, a).tolerance, 1e-3);
  b.tolerance = 1e-6;
  EXPECT_EQ(unidist::stricter(a, b).tolerance, 1e-6);
  a.relativeTolerance = 0.01;
  b.relativeTolerance = 0.1;
  EXPECT_EQ(unidist::stricter(a, b).relativeTolerance, 0.01);
  a.maxIterations = 10;
  EXPECT_EQ(unidist::stricter(a, b).maxIterations, b.maxIterations);
}

}  // namespace
