// unidist::Tracker on recorded trajectories: a ball (NURBS, mesh, point cloud or primitive) moved smoothly over a
// torus (NURBS, mesh or primitive) into and out of contact, across seams and patch boundaries, turning as it
// goes. At every step the tracked minima are compared with the global minimum — the closed form for the exact
// ball–torus pairs, else a cold global recomputation (unidist::contacts):
//  * the deepest tracked minimum equals the global minimum within tolerance whenever the latter is within the
//    cutoff — a step where it does not is a miss; misses are counted, and no miss may last longer than the
//    global period;
//  * no tracked minimum is below the global minimum (each is a realised pair of surface points);
//  * every tracked minimum is consistent (pointB − pointA = distance · normal, unit normal, within the cutoff);
//  * the penalty force is continuous: its change per step is bounded by the stiffness times the step's motion.
// Also: background passes converge to the same answer, the force's direction and torque, and bad options.
#include "unidist/contacts.h"
#include "unidist/mesh.h"
#include "unidist/nurbs.h"
#include "unidist/point_cloud.h"
#include "unidist/primitives.h"
#include "unidist/tracker.h"

#include "core/mesh_fixtures.h"
#include "core/nurbs_fixtures.h"
#include "core/tracker_trajectory.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <cmath>
#include <functional>
#include <memory>
#include <random>

namespace {

using unidist::Model;
using unidist::Tracker;
using unidist::TrackerOptions;
using Iso = Eigen::Isometry3d;
using Vec = Eigen::Vector3d;

using tracker_trajectory::kBall;
using tracker_trajectory::kR;
using tracker_trajectory::kTube;
using tracker_trajectory::Trajectory;

std::shared_ptr<const Model> nurbsBall() {
  return std::make_shared<unidist::NurbsModel>(std::vector<unidist::NurbsSurface>{nurbs_fixtures::sphereSurface(kBall)},
                                               true);
}
std::shared_ptr<const Model> nurbsTorus() {
  return std::make_shared<unidist::NurbsModel>(
      std::vector<unidist::NurbsSurface>{nurbs_fixtures::torusSurface(kR, kTube)}, true);
}
std::shared_ptr<const Model> meshOf(const meshfix::Soup& s) {
  auto m = std::make_shared<unidist::TriangleMesh>(s.vertices, s.triangles);
  m->buildStructures();
  return m;
}
std::shared_ptr<const Model> meshTorus() { return meshOf(meshfix::torus(kR, kTube, 48, 24)); }
std::shared_ptr<const Model> meshBall() { return meshOf(meshfix::icosphere(kBall, 3)); }
std::shared_ptr<const Model> cloudBall() {
  return std::make_shared<unidist::PointCloud>(meshfix::icosphere(kBall, 3).vertices);
}

std::string fmt(const Vec& v) {
  char b[96];
  std::snprintf(b, sizeof b, "(%.6f %.6f %.6f)", v.x(), v.y(), v.z());
  return b;
}

/// The exact signed distance of a ball (radius kBall, centred at the pose's origin) to the torus (kR, kTube) at
/// the origin: the centre's distance to the core circle less both radii (also the penetration depth: the ball
/// leaves along that line). For the exact ball–torus pairs the tracker is checked against this, not contacts().
double ballTorusTruth(const Iso& X_ball) {
  const Vec c = X_ball.translation();
  return std::hypot(std::hypot(c.x(), c.y()) - kR, c.z()) - kTube - kBall;
}

struct Stats {
  int checked = 0, misses = 0, longestMiss = 0, unsound = 0, inconsistent = 0, forceJumps = 0;
  double worstError = 0, worstJumpRatio = 0;
};

/// Runs the trajectory, comparing every step (or every `every`-th) with the global minimum: `truth` where the
/// pair has a closed form, else contacts() at the cutoff.
Stats run(const std::shared_ptr<const Model>& a, const std::shared_ptr<const Model>& b, const Trajectory& tr,
          TrackerOptions o, double tol, int every = 1, const std::function<double(const Iso&)>& truth = {}) {
  Tracker tracker(a, b, o);
  o = tracker.options();
  unidist::ContactOptions co;
  co.margin = o.cutoff;
  Stats s;
  int missRun = 0;
  Vec previousForce = Vec::Zero();
  Iso previous = Iso::Identity();
  const std::vector<Iso> poses = tr.poses();
  const double ballRadius = a->localBoundingSphere().radius + a->localBoundingSphere().center.norm();
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const unidist::TrackerUpdate& u = tracker.update(poses[i], Iso::Identity());
    for (const unidist::TrackedMinimum& m : tracker.minima()) {
      const bool ok = std::abs(m.normal.norm() - 1) < 1e-9 &&
                      (m.pointB - m.pointA - m.distance * m.normal).norm() <= 1e-6 && m.distance <= o.cutoff;
      s.inconsistent += ok ? 0 : 1;
      if (!ok && std::getenv("TRACKER_DEBUG"))
        std::printf("inconsistent step %zu: |n| %.17g gap %.3g d %.9g cutoff %.9g\n", i, m.normal.norm(),
                    (m.pointB - m.pointA - m.distance * m.normal).norm(), m.distance, o.cutoff);
    }
    // Force continuity: each engaged minimum's force changes by at most k × (its distance change ≤ the motion)
    // plus k × (d0 − d) × (its normal's turn); allow 4× the motion per minimum, plus a small absolute slack.
    if (i > 0) {
      const double motion = (poses[i].translation() - previous.translation()).norm() +
                            (poses[i].linear() - previous.linear()).norm() * ballRadius;
      const double allowed = o.stiffness * (4 * motion + 1e-3) * std::max<std::size_t>(1, tracker.minima().size());
      const double jump = (u.force - previousForce).norm();
      s.worstJumpRatio = std::max(s.worstJumpRatio, jump / allowed);
      s.forceJumps += jump > allowed ? 1 : 0;
    }
    previousForce = u.force;
    previous = poses[i];
    if (static_cast<int>(i) % every != 0) continue;
    const std::vector<unidist::Contact> ref =
        truth ? std::vector<unidist::Contact>{} : unidist::contacts(*a, poses[i], *b, Iso::Identity(), co);
    const double global = truth ? truth(poses[i]) : ref.empty() ? INFINITY : ref.front().distance;
    for (const unidist::TrackedMinimum& m : tracker.minima()) s.unsound += m.distance < global - tol ? 1 : 0;
    if (global > o.cutoff - tol) {
      missRun = 0;
      continue;  // nothing (or only a borderline minimum) to find
    }
    ++s.checked;
    const double tracked = tracker.minima().empty() ? INFINITY : tracker.minima().front().distance;
    const double error = std::abs(tracked - global);
    if (error <= tol) {
      missRun = 0;
      s.worstError = std::max(s.worstError, error);
    } else {
      ++s.misses;
      if (std::getenv("TRACKER_DEBUG")) {
        std::printf("miss step %zu global %.9g tracked %.9g (n %zu) pass %d merged %d added %d dropped %d\n", i, global,
                    tracked, tracker.minima().size(), u.globalPassStarted, u.globalPassMerged, u.added, u.dropped);
        for (const auto& m : tracker.minima())
          std::printf("   id %ld age %ld d %.9g pA %s\n", m.id, m.age, m.distance, fmt(m.pointA).c_str());
        if (!ref.empty()) std::printf("   ref pA %s\n", fmt(ref.front().pointA).c_str());
      }
      missRun += every;
      s.longestMiss = std::max(s.longestMiss, missRun);
    }
  }
  return s;
}

TrackerOptions inlineOptions() {
  TrackerOptions o;
  o.globalPass = unidist::GlobalPassMode::Inline;
  o.cutoff = 0.05;
  o.globalPeriod = 50;
  o.stiffness = 100;
  return o;
}

/// A trajectory of `steps` steps from `seed`.
Trajectory trajectory(unsigned seed, int steps = Trajectory().steps) {
  Trajectory tr;
  tr.seed = seed;
  tr.steps = steps;
  return tr;
}

/// Runs the trajectory with inlineOptions() (comparing every `every`-th step) and expects it tracked.
void expectTracks(const std::shared_ptr<const Model>& a, const std::shared_ptr<const Model>& b, const Trajectory& tr,
                  double tol, const char* what, int every = 1, const std::function<double(const Iso&)>& truth = {}) {
  SCOPED_TRACE(what);
  const TrackerOptions o = inlineOptions();
  const int period = o.globalPeriod;
  const Stats s = run(a, b, tr, o, tol, every, truth);
  EXPECT_GT(s.checked, 30) << "the trajectory must spend time within the cutoff";
  // Discrete models (clouds, facets) gain minima by birth, not only by motion: a point becoming the nearest, a
  // vertex passing an edge. The next pass finds them; so do few misses and none longer than the period.
  EXPECT_LE(s.longestMiss, period) << "a global minimum was missed for longer than the global period";
  EXPECT_LE(s.misses, s.checked / 50) << "misses: " << s.misses << " of " << s.checked;
  EXPECT_EQ(s.unsound, 0);
  EXPECT_EQ(s.inconsistent, 0);
  EXPECT_EQ(s.forceJumps, 0) << "worst jump / allowed: " << s.worstJumpRatio;
  std::printf("[%s] checked %d misses %d longest %d worst error %.3g worst force jump ratio %.3g\n", what, s.checked,
              s.misses, s.longestMiss, s.worstError, s.worstJumpRatio);
}

TEST(Tracker, NurbsBallOverNurbsTorus) {
  expectTracks(nurbsBall(), nurbsTorus(), trajectory(1, 240), 2e-6, "nurbs-nurbs", 1, ballTorusTruth);
}

TEST(Tracker, NurbsBallOverMeshTorus) { expectTracks(nurbsBall(), meshTorus(), trajectory(2), 2e-5, "nurbs-mesh"); }

TEST(Tracker, MeshBallOverMeshTorus) { expectTracks(meshBall(), meshTorus(), trajectory(3), 2e-5, "mesh-mesh"); }

TEST(Tracker, CloudBallOverMeshTorus) { expectTracks(cloudBall(), meshTorus(), trajectory(4), 2e-5, "cloud-mesh"); }

TEST(Tracker, PrimitiveBallOverPrimitiveTorus) {
  expectTracks(std::make_shared<unidist::Sphere>(kBall), std::make_shared<unidist::Torus>(kR, kTube), trajectory(5), 2e-6,
               "sphere-torus", 1, ballTorusTruth);
}

TEST(Tracker, PrimitiveCapsuleOverNurbsTorus) {
  Trajectory tr = trajectory(6, 100);
  tr.sweep = M_PI;  // half the path, every other step: a cold query of the overlapping pair takes ~0.1 s
  expectTracks(std::make_shared<unidist::Capsule>(kBall, 0.2), nurbsTorus(), tr, 2e-6, "capsule-nurbs", 2);
}

TEST(Tracker, BackgroundPassesReachTheSameMinima) {
  TrackerOptions o = inlineOptions();
  o.globalPass = unidist::GlobalPassMode::Background;
  const auto ball = nurbsBall(), torus = meshTorus();
  Tracker tracker(ball, torus, o);
  const std::vector<Iso> poses = trajectory(7).poses();
  for (const Iso& X : poses) tracker.update(X, Iso::Identity());
  // Hold the last pose until a pass started there has been merged: then nothing may be missing.
  for (int round = 0; round < 3; ++round) {
    tracker.waitForGlobalPass();
    tracker.update(poses.back(), Iso::Identity());
  }
  unidist::ContactOptions co;
  co.margin = tracker.options().cutoff;
  const auto ref = unidist::contacts(*ball, poses.back(), *torus, Iso::Identity(), co);
  ASSERT_FALSE(ref.empty()) << "the trajectory must end within the cutoff";
  ASSERT_FALSE(tracker.minima().empty());
  EXPECT_NEAR(tracker.minima().front().distance, ref.front().distance, 2e-5);
  EXPECT_GT(tracker.counters().globalPasses, 1);
}

TEST(Tracker, PenaltyForceTorqueAndDamping) {
  TrackerOptions o;
  o.globalPass = unidist::GlobalPassMode::Inline;
  o.cutoff = 0.05;
  o.stiffness = 100;
  o.damping = 0.1;
  o.timeStep = 1e-3;
  o.referencePoint_A = Vec(1, 0, 0);  // off the ball's centre: the contact force has a moment about it
  Tracker tracker(std::make_shared<unidist::Sphere>(1.0), std::make_shared<unidist::Box>(Vec(2, 2, 0.5)), o);
  const Iso X_WB = Iso(Eigen::Translation3d(0, 0, -0.5));  // top face at z = 0
  const unidist::TrackerUpdate far = tracker.update(Iso(Eigen::Translation3d(0, 0, 1.2)), X_WB);
  EXPECT_EQ(far.minima, 0);
  EXPECT_EQ(far.force.norm(), 0.0);
  tracker.update(Iso(Eigen::Translation3d(0, 0, 1.02)), X_WB);
  const unidist::TrackerUpdate& u = tracker.update(Iso(Eigen::Translation3d(0, 0, 1.01)), X_WB);
  ASSERT_EQ(u.minima, 1);
  EXPECT_NEAR(u.deepest, 0.01, 1e-9);
  // k (d0 − d) = 100 × 0.04 = 4, plus damping: the gap closed at 10 per second → 0.1 × 10 = 1; A pushed up.
  EXPECT_NEAR((u.force - Vec(0, 0, 5)).norm(), 0, 1e-6);
  // About r = (1, 0, 1.01), the reference point posed: (p − r) × F = (−1, 0, −1) × (0, 0, 5) = (0, 5, 0), where
  // p = (0, 0, 0.01) is the ball's contact point.
  EXPECT_NEAR((u.torque - Vec(0, 5, 0)).norm(), 0, 1e-6);
  const unidist::TrackedMinimum& m = tracker.minima().front();
  EXPECT_NEAR((m.normal - Vec(0, 0, -1)).norm(), 0, 1e-9);
  EXPECT_NEAR(m.force, 5, 1e-6);
  // Held still: the damping term vanishes.
  EXPECT_NEAR(tracker.update(Iso(Eigen::Translation3d(0, 0, 1.01)), X_WB).force.z(), 4, 1e-6);
}

TEST(Tracker, MinimaPushingTheSameWayShareOneSpring) {
  // A mesh cube face-down over a box: its four bottom corners are four minima with the same normal. Together they
  // push as one spring, k (d0 − d) = 100 × 0.04 = 4, not four times that, each with a quarter.
  TrackerOptions o;
  o.globalPass = unidist::GlobalPassMode::Inline;
  o.cutoff = 0.05;
  o.stiffness = 100;
  const meshfix::Soup cube = meshfix::gridBox(Vec(0.5, 0.5, 0.5), 1);
  Tracker tracker(std::make_shared<unidist::TriangleMesh>(cube.vertices, cube.triangles),
                  std::make_shared<unidist::Box>(Vec(2, 2, 0.5)), o);
  const Iso X_WB = Iso(Eigen::Translation3d(0, 0, -0.5));  // top face at z = 0
  const Iso X_WA = Iso(Eigen::Translation3d(0.1, -0.2, 0.51));
  tracker.update(X_WA, X_WB);
  const unidist::TrackerUpdate& u = tracker.update(X_WA, X_WB);
  ASSERT_GE(u.minima, 2);
  EXPECT_NEAR((u.force - Vec(0, 0, 4)).norm(), 0, 1e-6);
  for (const unidist::TrackedMinimum& m : tracker.minima()) EXPECT_NEAR(m.force, 4.0 / u.minima, 1e-6);
}

TEST(Tracker, RejectsBadInput) {
  const auto s = std::make_shared<unidist::Sphere>(1.0);
  auto make = [&](auto edit) {
    TrackerOptions o;
    edit(o);
    return Tracker(s, s, o).options().cutoff;
  };
  EXPECT_THROW(make([](TrackerOptions& o) { o.cutoff = NAN; }), unidist::InputError);
  EXPECT_THROW(make([](TrackerOptions& o) { o.globalPeriod = 0; }), unidist::InputError);
  EXPECT_THROW(make([](TrackerOptions& o) { o.cutoff = 0.1, o.penaltyDistance = 0.2; }), unidist::InputError);
  EXPECT_THROW(make([](TrackerOptions& o) { o.stiffness = -1; }), unidist::InputError);
  EXPECT_THROW(make([](TrackerOptions& o) { o.timeStep = 0; }), unidist::InputError);
  EXPECT_THROW(Tracker(nullptr, s), unidist::InputError);
  const auto plane = std::make_shared<unidist::Plane>(Vec::UnitZ(), 0.0);
  EXPECT_THROW(Tracker(plane, plane), unidist::InputError);
  Tracker t(s, s);
  Iso bad = Iso::Identity();
  bad.translation().x() = NAN;
  EXPECT_THROW(t.update(bad, Iso::Identity()), unidist::InputError);
  EXPECT_NEAR(make([](TrackerOptions&) {}), 0.02 * 2 * std::sqrt(3.0), 1e-12);  // 2% of the smaller diagonal
}

}  // namespace
