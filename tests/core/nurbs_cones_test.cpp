// The cone tests without trigonometry (patch_tree.h) against the angles themselves: they may only ever keep
// more than the exact rule would, and not much more.
#include "nurbs/patch_tree.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

namespace unidist {
namespace {

using Vec = Eigen::Vector3d;

constexpr double kPi = 3.14159265358979323846;

// The two cone tests against the angles themselves: never false where the exact answer is
// true (a node may only be dropped by a proof), and false wherever it is false by more than 1e-8 rad, tiny
// cones included (deep nodes of flat faces: a test on cosines alone kept their neighbours 6e-5 rad off).
TEST(NurbsCones, TestsAgreeWithTheAngles) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> U(-1, 1), A(0, 0.5 * kPi);
  int decided = 0;
  for (int k = 0; k < 200000; ++k) {
    // Every other case two tiny cones (deep nodes) with nearly parallel or nearly orthogonal axes.
    const bool tiny = k % 2 == 0;
    const Vec a = Vec(U(rng), U(rng), U(rng)).normalized();
    Vec b = Vec(U(rng), U(rng), U(rng)).normalized();
    if (tiny) {
      const Vec off = a.cross(b).normalized();
      b = k % 4 == 0 ? Vec((a + 1e-4 * U(rng) * off).normalized()) : Vec((off + 1e-4 * U(rng) * a).normalized());
    }
    const double alpha = tiny ? 1e-5 * A(rng) : A(rng);
    const double beta = tiny ? 1e-5 * A(rng) : A(rng) * (k % 3 == 0 ? 0.05 : 1.0);
    const nurbs::Cone ca = nurbs::makeCone(a, alpha), cb = nurbs::makeCone(b, beta);
    const double phi = std::atan2(a.cross(b).norm(), a.dot(b)), sum = alpha + beta;
    const double meet = std::min(phi, kPi - phi) - sum;  // <= 0: some direction of a within ±b
    const double orth = std::abs(phi - 0.5 * kPi) - sum;  // <= 0: some pair orthogonal
    const auto where = [&] {
      return "phi " + std::to_string(phi) + " angles " + std::to_string(alpha) + ", " + std::to_string(beta);
    };
    if (meet <= 0) {
      ASSERT_TRUE(nurbs::meetsEitherWay(ca, cb)) << where();
    }
    const bool clearlyApart = meet > 1e-8, clearlyNotOrthogonal = orth > 1e-8;
    if (clearlyApart) {
      ASSERT_FALSE(nurbs::meetsEitherWay(ca, cb)) << where();
    }
    if (orth <= 0) {
      ASSERT_TRUE(nurbs::canBeOrthogonal(ca, cb)) << where();
    }
    if (clearlyNotOrthogonal) {
      ASSERT_FALSE(nurbs::canBeOrthogonal(ca, cb)) << where();
    }
    decided += clearlyApart + clearlyNotOrthogonal;
  }
  EXPECT_GT(decided, 1000);
  // The cone towards q from a ball: every direction from a point of the ball to q is inside it.
  for (int k = 0; k < 2000; ++k) {
    const Vec c(U(rng), U(rng), U(rng)), q = 3 * Vec(U(rng), U(rng), U(rng));
    const double r = 0.5 * (1 + U(rng));
    const nurbs::Cone towards = nurbs::coneTowards(q, c, r);
    if (towards.all) continue;
    const Vec p = c + r * std::abs(U(rng)) * Vec(U(rng), U(rng), U(rng)).normalized();
    ASSERT_TRUE(nurbs::meetsEitherWay(towards, nurbs::makeCone((q - p).normalized(), 0.0)));
    EXPECT_NEAR(towards.sine, std::sin(towards.angle), 2e-9);
    EXPECT_NEAR(towards.cosine, std::cos(towards.angle), 2e-9);
  }
}

}  // namespace
}  // namespace unidist
