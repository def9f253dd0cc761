// The distance from the origin to the outside of a union of equal balls that hold it (generic/ball_union.h),
// against closed forms (one ball; balls all round a vertical axis, left straight up) and against a brute-force
// oracle: the union is star-shaped about the origin, so the distance is the least over directions of the last
// ball's exit along them, minimised over a direction grid and refined by a local pattern search.
#include "generic/ball_union.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

namespace unidist::detail {
namespace {

using Vec = Eigen::Vector3d;

/// Where the ray from the origin along unit u leaves every ball.
double lastExit(const std::vector<Vec>& centres, double radius, const Vec& u) {
  double exit = 0;
  for (const Vec& c : centres) {
    const double along = u.dot(c);
    exit = std::max(exit, along + std::sqrt(along * along - c.squaredNorm() + radius * radius));
  }
  return exit;
}

/// Is t outside every ball (to a hair)?
bool outsideAll(const std::vector<Vec>& centres, double radius, const Vec& t) {
  return std::all_of(centres.begin(), centres.end(), [&](const Vec& c) { return (t - c).norm() >= radius * (1 - 1e-13); });
}

/// The least |t| over the union's boundary, sampled: every sphere's point nearest the origin and a 4° grid on it,
/// and every circle where two spheres meet at 3,600 points, each of its lowest samples then refined by golden
/// section along the circle (the least lies on a sphere, on such a circle, or where the circles end at a third
/// sphere). From above.
double oracle(const std::vector<Vec>& centres, double radius) {
  double best = std::numeric_limits<double>::infinity();
  for (const Vec& c : centres) {
    const Vec nearest = c - radius * c.normalized();  // the sphere's own least, where no other ball covers it
    if (outsideAll(centres, radius, nearest)) best = std::min(best, nearest.norm());
  }
  for (const Vec& c : centres)
    for (int i = 0; i <= 45; ++i)
      for (int j = 0; j < 90; ++j) {
        const double theta = M_PI * i / 45, phi = 2 * M_PI * j / 90;
        const Vec t = c + radius * Vec(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
        if (t.norm() < best && outsideAll(centres, radius, t)) best = t.norm();
      }
  for (std::size_t i = 0; i < centres.size(); ++i)
    for (std::size_t j = i + 1; j < centres.size(); ++j) {
      const Vec d = centres[j] - centres[i], m = 0.5 * (centres[i] + centres[j]);
      if (d.norm() >= 2 * radius) continue;
      const double r = std::sqrt(radius * radius - 0.25 * d.squaredNorm());
      const Vec e1 = d.unitOrthogonal(), e2 = d.normalized().cross(e1);
      const auto at = [&](double angle) {
        const Vec t = m + r * (std::cos(angle) * e1 + std::sin(angle) * e2);
        return outsideAll(centres, radius, t) ? t.norm() : std::numeric_limits<double>::infinity();
      };
      constexpr int kSamples = 3600;
      for (int k = 0; k < kSamples; ++k) {
        const double step = 2 * M_PI / kSamples, mid = step * k;
        const double here = at(mid);
        if (!std::isfinite(here) || here > std::min(at(mid - step), at(mid + step))) continue;  // not a local least
        double lo = mid - step, hi = mid + step;
        for (int it = 0; it < 100; ++it) {
          const double x1 = hi - 0.618 * (hi - lo), x2 = lo + 0.618 * (hi - lo);
          (at(x1) < at(x2) ? hi : lo) = at(x1) < at(x2) ? x2 : x1;
        }
        best = std::min({best, here, at(0.5 * (lo + hi))});
      }
    }
  return best;
}

TEST(BallUnion, OneBallIsLeftStraightAwayFromItsCentre) {
  EXPECT_NEAR(outsideBallUnion({Vec(0.3, -0.1, 0.2)}, 1.0), 1.0 - std::sqrt(0.14), 1e-13);
  EXPECT_EQ(outsideBallUnion({Vec(2, 0, 0)}, 1.0), 0.0) << "a ball not holding the origin is no constraint";
  EXPECT_EQ(outsideBallUnion({}, 1.0), 0.0);
}

// Contacts all round a ring's hole: balls centred on a circle below the origin, each holding it by g. The way out
// is straight up, ~g / cos α where α is the centres' angle from the vertical (exactly: where the vertical leaves
// them), for any number of balls from three (evenly spread: every horizontal step moves towards one of them).
TEST(BallUnion, BallsAllRoundAreLeftUpTheAxis) {
  const double radius = 0.8, alpha = 1.26;
  for (int n : {3, 5, 12}) {
    for (double g : {1e-8, 1e-4, 1e-2}) {
      std::vector<Vec> centres;
      for (int k = 0; k < n; ++k) {
        const double around = 2 * M_PI * k / n;
        centres.push_back((radius - g) *
                          Vec(std::sin(alpha) * std::cos(around), std::sin(alpha) * std::sin(around), -std::cos(alpha)));
      }
      // |s ẑ − c|² = ρ² for every centre c: s = −(ρ − g) cos α + √((ρ − g)² cos² α + ρ² − (ρ − g)²), ~g / cos α.
      const double inner = (radius - g) * std::cos(alpha);
      const double up = -inner + std::sqrt(inner * inner + g * (2 * radius - g));
      EXPECT_NEAR(up, g / std::cos(alpha), 5 * g * g / std::pow(std::cos(alpha), 3));
      EXPECT_NEAR(lastExit(centres, radius, Vec::UnitZ()), up, 1e-15);
      EXPECT_NEAR(outsideBallUnion(centres, radius), up, 1e-12 + 1e-9 * up) << n << " balls, g " << g;
    }
  }
}

TEST(BallUnion, RandomUnionsMatchTheOracle) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 40; ++trial) {
    const double radius = 0.5 + 0.5 * (u(rng) + 1);
    std::vector<Vec> centres;
    const int n = 1 + trial % 7;
    while (static_cast<int>(centres.size()) < n) {
      const Vec c(u(rng), u(rng), u(rng));
      if (c.norm() < radius) centres.push_back(c);
    }
    const double expected = oracle(centres, radius);
    const double bound = outsideBallUnion(centres, radius);
    EXPECT_LE(bound, expected + 1e-12) << "a lower bound, trial " << trial;
    EXPECT_NEAR(bound, expected, 1e-7) << "and the distance itself, trial " << trial;
  }
}

}  // namespace
}  // namespace unidist::detail
