// The support ball (core/src/nurbs/support_ball.h) between a ring and a ball above it: every gap it proves between
// two nodes holds against dense sampling of both, whether a node's extremes were certified for it or inherited
// from its parent (a subpatch is no farther from the centre, and no nearer, than the patch holding it); and a
// sphere's children inherit its radius without certificates of their own.
#include "nurbs/patch_tree.h"
#include "nurbs/support_ball.h"
#include "nurbs_fixtures.h"
#include "nurbs_pair_helpers.h"
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

std::vector<Vec> samples(const PatchNode& n, const Eigen::Isometry3d& X) {
  std::vector<Vec> points;
  for (int a = 0; a <= 8; ++a)
    for (int b = 0; b <= 8; ++b) points.push_back(X * n.net.derivatives(a / 8.0, b / 8.0).point);
  return points;
}

/// The nodes one and two levels below the roots, each grandchild with its parent.
struct Family {
  std::vector<const PatchNode*> parents;
  std::vector<std::pair<const PatchNode*, const PatchNode*>> children;  // (node, parent)
};
Family familyOf(const NurbsModel& m, std::vector<std::unique_ptr<PatchNode>>& arena) {
  Family f;
  for (const auto& root : m.forest().roots)
    for (const PatchNode* c : m.forest().children(*root, arena)) {
      f.parents.push_back(c);
      for (const PatchNode* g : m.forest().children(*c, arena)) f.children.emplace_back(g, c);
    }
  return f;
}

TEST(SupportBall, InheritedAndCertifiedGapsHoldAgainstSampling) {
  const NurbsModel torus({nurbs_fixtures::torusSurface(1, 0.25)}, true);
  const NurbsModel ball({nurbs_fixtures::sphereSurface(0.4)}, true);
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<std::unique_ptr<PatchNode>> arena;
  const Family ofTorus = familyOf(torus, arena), ofBall = familyOf(ball, arena);
  int checked = 0, settled = 0;
  for (int pose = 0; pose < 5; ++pose) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation() = Vec(0.3 + 0.2 * u(rng), 0.2 + 0.2 * u(rng), 0.9 + 0.1 * u(rng));  // above the tube
    const nurbs_pair_helpers::ClosestPair c = nurbs_pair_helpers::closestPair(torus, ball, X);
    const double d = (c.pB - c.pA).norm();
    const std::optional<SupportBall> fitted =
        SupportBall::fit({torus.patches()[static_cast<std::size_t>(c.patchA)], c.xA,
                          ball.patches()[static_cast<std::size_t>(c.patchB)], c.xB, X, c.pA, c.pB});
    ASSERT_TRUE(fitted) << "pose " << pose;
    ASSERT_TRUE(fitted->innerIsB());  // the ball curves more
    EXPECT_NEAR(fitted->radius(), 0.4, 1e-9);
    // Parents first, as the search visits them, with what the query needs; then their children, which may
    // inherit.
    SupportBall separator = *fitted;
    const double needed = d - 1e-9;
    for (const PatchNode* pa : ofTorus.parents)
      for (const PatchNode* pb : ofBall.parents) (void)separator.gap(*pa, *pb, needed);
    // Every 11th / 13th grandchild, and the six nearest the closest pair (where the bounds are tight).
    const auto picked = [](const Family& f, const Vec& near, std::size_t stride) {
      std::vector<std::size_t> order(f.children.size());
      for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
      std::partial_sort(order.begin(), order.begin() + 6, order.end(), [&](std::size_t x, std::size_t y) {
        return (f.children[x].first->ball.center - near).norm() < (f.children[y].first->ball.center - near).norm();
      });
      order.resize(6);
      for (std::size_t k = 0; k < f.children.size(); k += stride) order.push_back(k);
      return order;
    };
    for (const std::size_t i : picked(ofTorus, c.pA, 11))
      for (const std::size_t j : picked(ofBall, X.inverse() * c.pB, 13)) {
        const auto [na, parentA] = ofTorus.children[i];
        const auto [nb, parentB] = ofBall.children[j];
        const double gap = separator.gap(*na, *nb, needed, parentA, parentB);
        if (!(gap > 0)) continue;
        ++checked;
        double sampled = std::numeric_limits<double>::infinity();
        for (const Vec& pa : samples(*na, Eigen::Isometry3d::Identity()))
          for (const Vec& pb : samples(*nb, X)) sampled = std::min(sampled, (pb - pa).norm());
        EXPECT_GE(sampled, gap - 1e-12) << "pose " << pose;
        settled += gap >= needed ? 1 : 0;
      }
  }
  EXPECT_GT(checked, 500);
  EXPECT_GT(settled, 0.9 * checked);  // the pairs the query needs settled, most by what their parents proved
}

}  // namespace
}  // namespace unidist::nurbs
