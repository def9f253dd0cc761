// Point clouds against brute force: nearest point, support, surface cells (down to single points), the
// generic branch and bound over a cloud, and validation.
#include "generic/surface_search.h"
#include "unidist/distance.h"
#include "unidist/point_cloud.h"
#include "unidist/primitives.h"

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <thread>

namespace {

using Vec = Eigen::Vector3d;
using unidist::InputError;
using unidist::PointCloud;
using unidist::SurfaceCell;
using unidist::SurfacePoint;

std::vector<Vec> randomCloud(int n, std::mt19937_64& rng, double scale = 1.0) {
  std::normal_distribution<double> n01;
  std::vector<Vec> pts;
  for (int i = 0; i < n; ++i) {
    // Points near a squashed sphere, plus some exact repeats (ties) every 50th.
    if (i % 50 == 49) {
      pts.push_back(pts[static_cast<std::size_t>(i / 2)]);
      continue;
    }
    const Vec d = Vec(n01(rng), n01(rng), 0.5 * n01(rng)).normalized();
    pts.push_back(scale * (d + 0.01 * Vec(n01(rng), n01(rng), n01(rng))));
  }
  return pts;
}

std::size_t bruteNearest(const std::vector<Vec>& pts, const Vec& q) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < pts.size(); ++i)
    if ((pts[i] - q).squaredNorm() < (pts[best] - q).squaredNorm()) best = i;
  return best;
}

TEST(PointCloud, NearestPointMatchesBruteForceAtEveryScale) {
  for (double scale : {1e-4, 1.0, 1e4}) {
    std::mt19937_64 rng(31);
    const std::vector<Vec> pts = randomCloud(3000, rng, scale);
    const PointCloud cloud(pts);
    std::uniform_real_distribution<double> u(-1.5 * scale, 1.5 * scale);
    for (int i = 0; i < 3000; ++i) {
      const Vec q = i % 3 == 0 ? pts[static_cast<std::size_t>(i)] : Vec(u(rng), u(rng), u(rng));
      const SurfacePoint s = cloud.closestPoint(q);
      const std::size_t truth = bruteNearest(pts, q);
      const double d = (pts[truth] - q).norm();  // ties may pick another point at the same distance
      ASSERT_LE(std::abs(d - s.signedDistance), 4e-16 * d) << i;
      ASSERT_EQ(pts[static_cast<std::size_t>(s.feature)], s.point) << i;
      ASSERT_GE(s.signedDistance, 0);
      ASSERT_NEAR(s.normal.norm(), 1.0, 1e-15);
      if (s.signedDistance > 0) {
        ASSERT_LE((s.normal - (q - s.point).normalized()).norm(), 1e-15);
      }
    }
    EXPECT_FALSE(cloud.isSolid());
    EXPECT_FALSE(cloud.inside(Vec::Zero()));
    EXPECT_EQ(cloud.type(), unidist::ModelType::PointCloud);
  }
}

TEST(PointCloud, NormalWhereTheQueryCoincidesWithAPoint) {
  const std::vector<Vec> pts = {{0, 0, 0}, {1, 0, 0}, {0, 2, 0}};
  const PointCloud bare(pts);
  EXPECT_EQ(bare.closestPoint(Vec(1, 0, 0)).normal, Vec::UnitZ());
  EXPECT_EQ(bare.closestPoint(Vec(1, 0, 0)).feature, 1);
  EXPECT_EQ(bare.closestPoint(Vec(1, 0, 0)).signedDistance, 0.0);
  const PointCloud withNormals(pts, {{0, 0, 3}, {0, -2, 0}, {0, 0, 0}});
  EXPECT_EQ(withNormals.closestPoint(Vec(1, 0, 0)).normal, Vec(0, -1, 0));  // stored, normalised
  EXPECT_EQ(withNormals.closestPoint(Vec(0, 2, 0)).normal, Vec::UnitZ());   // a zero normal means none
  EXPECT_LE((withNormals.closestPoint(Vec(0.6, 2.8, 0)).normal - Vec(0.6, 0.8, 0)).norm(), 1e-15);
  EXPECT_EQ(withNormals.normals()[0], Vec(0, 0, 1));
}

TEST(PointCloud, BadInputIsRejectedWithTheReason) {
  const auto message = [](std::vector<Vec> p, std::vector<Vec> n) {
    try {
      PointCloud c(std::move(p), std::move(n));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message({}, {}), "point cloud: no points");
  EXPECT_EQ(message({{0, 0, 0}, {1, NAN, 2}}, {}), "point cloud: point 1 has a non-finite coordinate (1, nan, 2)");
  EXPECT_EQ(message({{0, 0, 0}, {1, 1, 2}}, {{0, 0, 1}}), "point cloud: 1 normals for 2 points");
  EXPECT_EQ(message({{0, 0, 0}}, {{0, INFINITY, 1}}), "point cloud: normal 0 has a non-finite coordinate (0, inf, 1)");
  EXPECT_EQ(message({{0, 0, 0}}, {}), "no error");
}

TEST(PointCloud, SupportIsTheBestPoint) {
  std::mt19937_64 rng(2);
  const std::vector<Vec> pts = randomCloud(500, rng);
  const PointCloud cloud(pts);
  std::normal_distribution<double> n01;
  for (int i = 0; i < 500; ++i) {
    const Vec d(n01(rng), n01(rng), n01(rng));
    double best = -1e300;
    for (const Vec& p : pts) best = std::max(best, d.dot(p));
    ASSERT_EQ(d.dot(cloud.support(d)), best);
  }
}

// Cells: nodes with proved balls; leaves split into one-point cells of radius 0, which split no further.
TEST(PointCloud, CellsCoverEveryPointAndEndInSinglePoints) {
  std::mt19937_64 rng(6);
  const std::vector<Vec> pts = randomCloud(700, rng);
  const PointCloud cloud(pts);
  std::vector<SurfaceCell> cells = cloud.surfaceCells();
  std::vector<int> reached(pts.size(), 0);
  int levels = 0;
  for (bool splitting = true; splitting;) {
    splitting = false;
    for (const Vec& p : pts) {
      bool covered = false;
      for (const SurfaceCell& c : cells) covered = covered || (p - c.center).norm() <= c.radius;
      ASSERT_TRUE(covered) << "level " << levels;
    }
    std::vector<SurfaceCell> next;
    for (const SurfaceCell& c : cells) {
      ASSERT_LE((c.sample - c.center).norm(), c.radius);
      const std::size_t before = next.size();
      cloud.splitCell(c, next);
      if (c.radius == 0) {
        ASSERT_EQ(next.size(), before);  // nothing smaller than a point: the cell stays as it is
        ASSERT_EQ(c.center, c.sample);
        next.push_back(c);
        continue;
      }
      splitting = true;
    }
    cells = std::move(next);
    ASSERT_LT(++levels, 200);
  }
  for (const SurfaceCell& c : cells) {
    ASSERT_EQ(c.radius, 0);
    for (std::size_t i = 0; i < pts.size(); ++i) reached[i] += pts[i] == c.sample;
  }
  for (int r : reached) EXPECT_GE(r, 1);
}

// The generic branch and bound pops cells and splits them; a one-point cell has lower bound = its value, so it
// is never popped before the search stops, and when popped it adds nothing. The minimum over the cloud of a
// box's signed distance must come out exact, with the lower bound equal to it.
TEST(PointCloud, GenericBranchAndBoundReachesTheExactMinimum) {
  std::mt19937_64 rng(12);
  const std::vector<Vec> pts = randomCloud(2000, rng);
  const PointCloud cloud(pts);
  const unidist::Box box(Vec(0.3, 0.2, 0.25));
  const auto boxSd = [&](const Vec& p) {
    const Vec d = p.cwiseAbs() - Vec(0.3, 0.2, 0.25);
    return d.cwiseMax(0.0).norm() + std::min(d.maxCoeff(), 0.0);
  };
  for (int trial = 0; trial < 6; ++trial) {
    Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
    X_WB.linear() = Eigen::Quaterniond::UnitRandom().toRotationMatrix();
    X_WB.translation() = Vec(0.4 * trial - 1.0, 0.1, -0.2);
    double truth = 1e300;
    for (const Vec& p : pts) truth = std::min(truth, boxSd(X_WB.inverse() * p));
    const unidist::detail::PosedModel c{cloud, Eigen::Isometry3d::Identity()}, b{box, X_WB};
    const auto m = unidist::detail::minimizeFieldOverSurface(c, b, 1e300, Vec::Zero(), 0.0, 1000000);
    EXPECT_FALSE(m.exhausted);
    EXPECT_NEAR(m.value, truth, 1e-15);
    EXPECT_NEAR(m.lowerBound, truth, 1e-15);
    const auto r = unidist::distance(cloud, Eigen::Isometry3d::Identity(), box, X_WB);
    SCOPED_TRACE(r.method);
    EXPECT_NEAR(r.distance, truth, 1e-12);
    EXPECT_LE(r.lowerBound, truth + 1e-12);
    EXPECT_GE(r.upperBound, truth - 1e-12);
  }
}

TEST(PointCloud, TreeBuiltOnceUnderConcurrentQueries) {
  std::mt19937_64 rng(8);
  const std::vector<Vec> pts = randomCloud(20000, rng);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  std::vector<Vec> queries;
  for (int i = 0; i < 3000; ++i) queries.emplace_back(u(rng), u(rng), u(rng));
  const PointCloud reference(pts);
  std::vector<int> expected;
  for (const Vec& q : queries) expected.push_back(reference.closestPoint(q).feature);
  const PointCloud fresh(pts);
  const std::size_t before = fresh.memoryBytes();
  std::vector<int> mismatches(8, 0);
  std::vector<std::thread> threads;
  for (int k = 0; k < 8; ++k)
    threads.emplace_back([&, k] {
      for (std::size_t i = 0; i < queries.size(); ++i)
        mismatches[static_cast<std::size_t>(k)] += fresh.closestPoint(queries[i]).feature != expected[i];
    });
  for (auto& t : threads) t.join();
  for (int m : mismatches) EXPECT_EQ(m, 0);
  EXPECT_EQ(fresh.treeBuildCount(), 1);
  EXPECT_GT(fresh.memoryBytes(), before);
  EXPECT_EQ(fresh.memoryBytes(), reference.memoryBytes());
  EXPECT_EQ(fresh.describe(), "point cloud: 20000 points");
}

}  // namespace
