// Queries are const and thread-safe, lazy structures included: several threads run thousands of queries on
// shared models that have built nothing yet (so the threads race to build BVHs, point trees and patch trees),
// each in its own order, and every answer must agree with a single-threaded run on separate, identical models.
// Run it under ThreadSanitizer (-DUNIDIST_SANITIZE=thread) to prove the absence of data races, not just of
// wrong answers.
#include "core/mesh_fixtures.h"
#include "core/nurbs_fixtures.h"
#include "unidist/distance.h"
#include "unidist/mesh.h"
#include "unidist/nurbs.h"
#include "unidist/point_cloud.h"
#include "unidist/primitives.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <random>
#include <thread>

namespace {

using unidist::Model;
using Vec = Eigen::Vector3d;
using Models = std::vector<std::shared_ptr<const Model>>;

constexpr double kTolerance = 1e-9;

constexpr int kNurbsBall = 2, kBox = 5, kCapsule = 6;  // indices in freshModels()

/// One of each representation, none of which has built anything yet.
Models freshModels() {
  std::vector<Vec> cloud;
  for (int i = 0; i < 400; ++i) {
    const double t = 0.1 * i, z = -0.5 + i / 400.0;
    cloud.emplace_back(0.4 * std::cos(t), 0.4 * std::sin(t), z);  // a helix
  }
  const auto mesh = [](const meshfix::Soup& s) { return std::make_shared<unidist::TriangleMesh>(s.vertices, s.triangles); };
  return {mesh(meshfix::torus(0.5, 0.15, 48, 24)), mesh(meshfix::icosphere(0.5, 3)),
          std::make_shared<unidist::NurbsModel>(std::vector<unidist::NurbsSurface>{nurbs_fixtures::sphereSurface(0.5)}, true),
          std::make_shared<unidist::NurbsModel>(std::vector<unidist::NurbsSurface>{nurbs_fixtures::torusSurface(0.5, 0.15)},
                                                true),
          std::make_shared<unidist::PointCloud>(cloud),
          std::make_shared<unidist::Box>(Vec(0.3, 0.4, 0.5)),
          std::make_shared<unidist::Capsule>(0.2, 0.3)};
}

/// A query: a model pair at a relative pose (separated: overlapping non-convex pairs are slow and prove
/// nothing more here), or a point against one model.
struct Query {
  int a = 0, b = -1;  // b < 0: point query on a
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  Vec point = Vec::Zero();
};

struct Answer {
  double value = 0, lower = 0, upper = 0;
};

std::vector<Query> queries(int modelCount) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Query> out;
  for (int a = 0; a < modelCount; ++a) {
    for (int b = a; b < modelCount; ++b) {
      for (double gap : {1.6, 2.0}) {
        Query q;
        q.a = a;
        q.b = b;
        q.X_WB = Eigen::Translation3d(Vec(u(rng), u(rng), u(rng)).normalized() * gap) *
                 Eigen::AngleAxisd(3 * u(rng), Vec(u(rng), u(rng), u(rng)).normalized());
        out.push_back(q);
      }
    }
    for (int i = 0; i < 200; ++i) {
      Query q;
      q.a = a;
      q.point = Vec(u(rng), u(rng), u(rng));
      out.push_back(q);
    }
  }
  // Overlaps of the NURBS ball (proved convex on first use, which the threads race to decide) with itself, the box
  // and the capsule: EPA on its support map.
  for (int b : {kNurbsBall, kBox, kCapsule})
    for (int k = 0; k < 3; ++k) {
      Query q;
      q.a = kNurbsBall;
      q.b = b;
      q.X_WB = Eigen::Translation3d(Vec(u(rng), u(rng), u(rng)).normalized() * 0.6) *
               Eigen::AngleAxisd(3 * u(rng), Vec(u(rng), u(rng), u(rng)).normalized());
      out.push_back(q);
    }
  return out;
}

Answer run(const Models& models, const Query& q) {
  if (q.b < 0) {
    const unidist::SurfacePoint p = models[q.a]->closestPoint(q.point);
    return {p.signedDistance, p.signedDistance, p.signedDistance};
  }
  unidist::DistanceOptions options;
  options.tolerance = kTolerance;
  const unidist::DistanceResult r =
      unidist::distance(*models[q.a], Eigen::Isometry3d::Identity(), *models[q.b], q.X_WB, options);
  return {r.distance, r.lowerBound, r.upperBound};
}

TEST(ThreadSafety, ConcurrentQueriesOnSharedLazyModelsMatchASingleThreadedRun) {
  const std::vector<Query> all = queries(static_cast<int>(freshModels().size()));
  const Models reference = freshModels();
  std::vector<Answer> expected;
  for (const Query& q : all) expected.push_back(run(reference, q));

  const Models shared = freshModels();  // nothing built: the threads race to build it
  constexpr int kThreads = 4;
  std::vector<std::vector<std::pair<std::size_t, Answer>>> got(kThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      std::vector<std::size_t> order(all.size());
      for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
      std::shuffle(order.begin(), order.end(), std::mt19937_64(100 + t));  // each thread its own order
      for (std::size_t i : order) got[t].emplace_back(i, run(shared, all[i]));
    });
  }
  for (std::thread& th : threads) th.join();

  long compared = 0;
  for (const auto& answers : got) {
    for (const auto& [i, a] : answers) {
      const Answer& e = expected[i];
      // Point queries are exact and must agree to rounding; distances are certified to the tolerance, so two
      // runs agree within twice that and each lies inside the other's proved bounds.
      const double allowance = all[i].b < 0 ? 1e-12 : 2 * kTolerance + 1e-12;
      ASSERT_NEAR(a.value, e.value, allowance) << "query " << i << " (models " << all[i].a << ", " << all[i].b << ")";
      ASSERT_LE(a.lower, e.upper + 1e-12);
      ASSERT_GE(a.upper, e.lower - 1e-12);
      ++compared;
    }
  }
  EXPECT_EQ(compared, kThreads * static_cast<long>(all.size()));
}

}  // namespace
