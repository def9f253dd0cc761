// The tube separator (core/src/nurbs/support_tube.h): fitted to a ring's inside it is the ring's own core
// circle; every separation it proves between two nodes holds against dense sampling of both; and linked rings,
// where neither a plane nor a ball separates, are certified exactly at every scale.
#include "bench/nurbs_truth.h"
#include "nurbs/patch_tree.h"
#include "nurbs/support_tube.h"
#include "nurbs_fixtures.h"
#include "nurbs_pair_helpers.h"
#include "unidist/distance.h"
#include "unidist/nurbs.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <vector>

namespace unidist::nurbs {
namespace {

using Vec = Eigen::Vector3d;

const nurbs_truth::Placement& linked() {
  static const std::vector<nurbs_truth::Placement> all = nurbs_truth::placements();
  return *std::find_if(all.begin(), all.end(),
                       [](const auto& p) { return std::string(p.name) == "torus-torus linked offset"; });
}

std::optional<SupportTube> fitTo(const NurbsModel& torus, const Eigen::Isometry3d& X_AB, double needed, double tol) {
  const nurbs_pair_helpers::ClosestPair c = nurbs_pair_helpers::closestPair(torus, torus, X_AB);
  return SupportTube::fit({torus.patches()[static_cast<std::size_t>(c.patchA)], c.xA,
                           torus.patches()[static_cast<std::size_t>(c.patchB)], c.xB, X_AB, c.pA, c.pB},
                          needed, tol);
}

TEST(SupportTube, FitsTheRingsOwnCoreCircle) {
  const NurbsModel torus({nurbs_fixtures::torusSurface(1, 0.25)}, true);
  std::optional<SupportTube> tube = fitTo(torus, linked().X_WB, linked().truth - 5e-10, 1e-9);
  ASSERT_TRUE(tube.has_value());
  EXPECT_NEAR(tube->coreRadius(), 1.0, 1e-12);
  // Every root patch of the ring whose inside it is lies inside it, and the other ring outside its wider tube
  // only away from the contact: no pair with A's root is settled at the roots.
  std::vector<std::unique_ptr<PatchNode>> arena;
  const PatchForest& forest = torus.forest();
  int settled = 0;
  for (const auto& a : forest.roots)
    for (const auto& b : forest.roots) settled += tube->gap(*a, *b) > 0;
  EXPECT_GT(settled, 0);
  EXPECT_LT(settled, 256);
}

// Whatever pair of nodes the tube separates is that far apart: checked by sampling both subpatches densely
// (the sampled distance can only exceed the true one), on rings in random linked-like poses.
TEST(SupportTube, ProvedGapsHoldAgainstSampling) {
  const NurbsModel torus({nurbs_fixtures::torusSurface(1, 0.25)}, true);
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> jitter(-0.15, 0.15);
  std::vector<std::unique_ptr<PatchNode>> arena;
  int checked = 0;
  for (int pose = 0; pose < 6; ++pose) {
    Eigen::Isometry3d X = linked().X_WB;
    X.translation() += Vec(jitter(rng), jitter(rng), jitter(rng));
    X.linear() = X.linear() * Eigen::AngleAxisd(jitter(rng), Vec(jitter(rng), jitter(rng), 1).normalized()).toRotationMatrix();
    const double truth = nurbs_truth::circleCircle({Vec::Zero(), Vec::UnitZ(), 1},
                                                   {X.translation(), X.linear() * Vec::UnitZ(), 1}) - 0.5;
    if (truth < 0.05) continue;
    std::optional<SupportTube> tube = fitTo(torus, X, truth - 1e-6, 1e-6);
    if (!tube) continue;
    // Nodes two levels down on both rings.
    std::vector<const PatchNode*> nodes;
    for (const auto& root : torus.forest().roots)
      for (const PatchNode* c : torus.forest().children(*root, arena))
        for (const PatchNode* g : torus.forest().children(*c, arena)) nodes.push_back(g);
    const auto samples = [&](const PatchNode& n, const Eigen::Isometry3d& X_) {
      std::vector<Vec> points;
      for (int a = 0; a <= 10; ++a)
        for (int b = 0; b <= 10; ++b) points.push_back(X_ * n.net.derivatives(a / 10.0, b / 10.0).point);
      return points;
    };
    int checkedHere = 0;
    for (std::size_t i = 0; i < nodes.size(); i += 7)
      for (std::size_t j = 0; j < nodes.size() && checkedHere < 40; j += 5) {
        const double gap = tube->gap(*nodes[i], *nodes[j]);
        if (!(gap > 0)) continue;
        ++checked;
        ++checkedHere;
        double sampled = std::numeric_limits<double>::infinity();
        for (const Vec& pa : samples(*nodes[i], Eigen::Isometry3d::Identity()))
          for (const Vec& pb : samples(*nodes[j], X)) sampled = std::min(sampled, (pb - pa).norm());
        EXPECT_GE(sampled, gap - 1e-12) << "pose " << pose;
      }
  }
  EXPECT_GT(checked, 50);
}

// A tube fitted at a higher best pair (an early Newton end), used, then narrowed to the tube fitted at the
// minimum: it settles exactly the pairs the fresh tube settles (its proofs for the wider tube hold for the
// narrower one), each by a gap that holds against sampling. It refuses a wider tube and another pose's.
TEST(SupportTube, NarrowedTubeSettlesWhatAFreshOneDoes) {
  const NurbsModel torus({nurbs_fixtures::torusSurface(1, 0.25)}, true);
  const Eigen::Isometry3d& X = linked().X_WB;
  const double tolerance = 1e-9;
  std::optional<SupportTube> early = fitTo(torus, X, linked().truth + 2e-3, tolerance);
  std::optional<SupportTube> fresh = fitTo(torus, X, linked().truth - 0.5 * tolerance, tolerance);
  ASSERT_TRUE(early && fresh);
  std::vector<std::unique_ptr<PatchNode>> arena;
  std::vector<const PatchNode*> nodes;
  for (const auto& root : torus.forest().roots) {
    nodes.push_back(root.get());
    for (const PatchNode* c : torus.forest().children(*root, arena)) nodes.push_back(c);
  }
  for (const PatchNode* a : nodes)
    for (const PatchNode* b : nodes) early->gap(*a, *b);  // proofs and refusals for the wider tube
  SupportTube wider = *early;
  EXPECT_FALSE(fresh->narrowTo(wider, 1e-12)) << "a wider tube is no narrowing";
  Eigen::Isometry3d moved = X;
  moved.translation().y() += 0.01;
  std::optional<SupportTube> elsewhere = fitTo(torus, moved, linked().truth - 0.05, tolerance);
  ASSERT_TRUE(elsewhere.has_value());
  EXPECT_FALSE(wider.narrowTo(*elsewhere, 1e-12)) << "another pose's circle in B's frame";
  ASSERT_TRUE(early->narrowTo(*fresh, 1e-12));
  const auto samples = [&](const PatchNode& n, const Eigen::Isometry3d& X_) {
    std::vector<Vec> points;
    for (int a = 0; a <= 8; ++a)
      for (int b = 0; b <= 8; ++b) points.push_back(X_ * n.net.derivatives(a / 8.0, b / 8.0).point);
    return points;
  };
  int settledNarrowed = 0, settledFresh = 0, sampledPairs = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i)
    for (std::size_t j = 0; j < nodes.size(); ++j) {
      const double gap = early->gap(*nodes[i], *nodes[j]);
      settledNarrowed += gap > 0;
      settledFresh += fresh->gap(*nodes[i], *nodes[j]) > 0;
      if (!(gap > 0) || (i * nodes.size() + j) % 37 != 0) continue;
      ++sampledPairs;
      double sampled = std::numeric_limits<double>::infinity();
      for (const Vec& pa : samples(*nodes[i], Eigen::Isometry3d::Identity()))
        for (const Vec& pb : samples(*nodes[j], X)) sampled = std::min(sampled, (pb - pa).norm());
      EXPECT_GE(sampled, gap - 1e-12);
      EXPECT_GE(gap, linked().truth - 0.5 * tolerance - 1e-12);
    }
  EXPECT_EQ(settledNarrowed, settledFresh);
  EXPECT_GT(settledFresh, 0);
  EXPECT_GT(sampledPairs, 10);
}

// Linked rings: the tube settles the pairs along the long stretch where they pass close; certified to the
// tolerance at tiny and huge scales, and in offset poses around the benchmark's.
TEST(SupportTube, LinkedRingsAreCertifiedAtEveryScale) {
  for (double scale : {1e-4, 1.0, 1e4}) {
    const auto torus = nurbs_pair_helpers::solid(nurbs_fixtures::torusSurface(1, 0.25, scale));
    for (const Vec& shift : {Vec(0, 0, 0), Vec(0, -0.05, 0.1), Vec(0.05, 0.05, -0.03)}) {
      Eigen::Isometry3d X = linked().X_WB;
      X.translation() = (X.translation() + shift) * scale;
      const double truth = scale * (nurbs_truth::circleCircle({Vec::Zero(), Vec::UnitZ(), 1},
                                                              {X.translation() / scale, X.linear() * Vec::UnitZ(), 1}) -
                                    0.5);
      for (double tolerance : {1e-6, 1e-9}) {
        SCOPED_TRACE(::testing::Message() << "scale " << scale << " shift " << shift.transpose() << " tol " << tolerance);
        DistanceOptions opt;
        opt.tolerance = tolerance * scale;
        const DistanceResult r = distance(*torus, Eigen::Isometry3d::Identity(), *torus, X, opt);
        EXPECT_EQ(r.status, Status::Certified);
        EXPECT_LE(r.upperBound - r.lowerBound, opt.tolerance);
        nurbs_pair_helpers::expectBracket(r, truth, 1e-12 * scale);
      }
    }
  }
}

}  // namespace
}  // namespace unidist::nurbs
