// Mesh–mesh separation distance: unidist (core/src/pairs/mesh_mesh.cpp) against FCL's BVHModel<OBBRSS> and
// <RSS> on the same meshes and poses, in the same run. Prints one line per case: distances, the largest
// relative difference to FCL, and median query times (µs). Usage:
//   unidist_bench_mesh_vs_fcl [models dir (torus_1k.obj, torus_20k.obj)] [fcl data dir (env.obj, rob.obj)] [tori|env|clouds|build]
#include "unidist/adapters/load.h"
#include "unidist/distance.h"
#include "unidist/mesh.h"
#include "unidist/point_cloud.h"

#include <fcl/fcl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

template <class BV>
std::shared_ptr<fcl::BVHModel<BV>> fclMesh(const unidist::TriangleMesh& m) {
  auto g = std::make_shared<fcl::BVHModel<BV>>();
  std::vector<fcl::Vector3d> v(m.vertices().begin(), m.vertices().end());
  std::vector<fcl::Triangle> t;
  for (const auto& tri : m.triangles()) t.emplace_back(tri[0], tri[1], tri[2]);
  g->beginModel();
  g->addSubModel(v, t);
  g->endModel();
  return g;
}

template <class F>
double medianMicros(int reps, F&& f) {
  std::vector<double> times;
  for (int i = 0; i < reps; ++i) {
    const auto t0 = Clock::now();
    f();
    times.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
  }
  std::nth_element(times.begin(), times.begin() + reps / 2, times.end());
  return times[static_cast<std::size_t>(reps / 2)];
}

template <class BV>
double fclDistance(const std::shared_ptr<fcl::BVHModel<BV>>& a, const Eigen::Isometry3d& Xa,
                   const std::shared_ptr<fcl::BVHModel<BV>>& b, const Eigen::Isometry3d& Xb) {
  fcl::DistanceRequestd request;
  request.enable_nearest_points = true;
  fcl::DistanceResultd result;
  fcl::Transform3d Ta = fcl::Transform3d::Identity(), Tb = fcl::Transform3d::Identity();
  Ta.linear() = Xa.linear();
  Ta.translation() = Xa.translation();
  Tb.linear() = Xb.linear();
  Tb.translation() = Xb.translation();
  fcl::distance(a.get(), Ta, b.get(), Tb, request, result);
  return result.min_distance;
}

struct Case {
  std::string name;
  Eigen::Isometry3d Xa, Xb;
};

void run(const std::string& label, const unidist::TriangleMesh& a, const unidist::TriangleMesh& b,
         const std::vector<Case>& cases, int reps) {
  const auto oa = fclMesh<fcl::OBBRSSd>(a), ob = fclMesh<fcl::OBBRSSd>(b);
  const auto ra = fclMesh<fcl::RSSd>(a), rb = fclMesh<fcl::RSSd>(b);
  (void)unidist::distance(a, Eigen::Isometry3d::Identity(), b, Eigen::Isometry3d::Identity());  // build BVHs
  for (const Case& c : cases) {
    const unidist::DistanceResult r = unidist::distance(a, c.Xa, b, c.Xb);
    const double fo = fclDistance(oa, c.Xa, ob, c.Xb);
    const double fr = fclDistance(ra, c.Xa, rb, c.Xb);
    const double tOurs = medianMicros(reps, [&] { (void)unidist::distance(a, c.Xa, b, c.Xb); });
    const double tObb = medianMicros(reps, [&] { (void)fclDistance(oa, c.Xa, ob, c.Xb); });
    const double tRss = medianMicros(reps, [&] { (void)fclDistance(ra, c.Xa, rb, c.Xb); });
    const double rel = std::abs(r.distance - fo) / std::max(1e-300, std::abs(fo));
    std::printf("%-22s %-16s ours %.12g [%s, %s, %d node pairs]  fcl-obbrss %.12g  rel.diff %.1e  |  "
                "median us: ours %.1f  obbrss %.1f  rss %.1f (rss d %.12g)\n",
                label.c_str(), c.name.c_str(), r.distance, toString(r.status), r.method, r.iterations, fo, rel, tOurs,
                tObb, tRss, fr);
  }
}

/// B's translation along x so that the distance is `gap` (bisection on our own distance, outside the timing).
Eigen::Isometry3d placeAtGap(const unidist::TriangleMesh& a, const unidist::TriangleMesh& b, Eigen::Isometry3d Xb,
                             double gap) {
  double lo = 0, hi = 10 * (a.localBounds().diagonal() + b.localBounds().diagonal());
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    Xb.translation().x() = mid;
    const double d = unidist::distance(a, Eigen::Isometry3d::Identity(), b, Xb).distance;
    (d < gap ? lo : hi) = mid;
    if (std::abs(d - gap) < 1e-3 * gap) break;
  }
  return Xb;
}

/// Hierarchy build time, ours (the BVH alone, on a freshly constructed mesh) against FCL's BVHModel build.
void buildTimes(const std::string& label, const unidist::TriangleMesh& m, int reps) {
  std::vector<double> ours;
  for (int i = 0; i < reps; ++i) {
    const unidist::TriangleMesh fresh(m.vertices(), m.triangles());
    const auto t0 = Clock::now();
    (void)fresh.bvh();
    ours.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
  }
  std::nth_element(ours.begin(), ours.begin() + reps / 2, ours.end());
  const double tObb = medianMicros(reps, [&] { (void)fclMesh<fcl::OBBRSSd>(m); });
  const double tRss = medianMicros(reps, [&] { (void)fclMesh<fcl::RSSd>(m); });
  std::printf("%-22s build  %zu triangles  median ms: ours %.3f  fcl-obbrss %.3f  fcl-rss %.3f  (fcl/ours %.1fx)\n",
              label.c_str(), m.triangles().size(), ours[static_cast<std::size_t>(reps / 2)] / 1000, tObb / 1000,
              tRss / 1000, std::min(tObb, tRss) / ours[static_cast<std::size_t>(reps / 2)]);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string models = argc > 1 ? argv[1] : "/work/shared/acceptance/models";
  const std::string fclData = argc > 2 ? argv[2] : "/work/shared/data/fcl";
  auto mesh = [](const std::string& path) {
    auto m = std::dynamic_pointer_cast<const unidist::TriangleMesh>(unidist::loadModel(path));
    if (!m) throw std::runtime_error(path + " is not a mesh");
    return m;
  };
  const auto t1 = mesh(models + "/torus_1k.obj"), t20 = mesh(models + "/torus_20k.obj");
  const auto env = mesh(fclData + "/env.obj"), rob = mesh(fclData + "/rob.obj");

  const std::string only = argc > 3 ? argv[3] : "";  // "tori", "env", "clouds" or "build": one group only
  if (only.empty() || only == "build") {
    buildTimes("torus_1k", *t1, 21);
    buildTimes("torus_20k", *t20, 11);
    buildTimes("env", *env, 21);
    if (only == "build") return 0;
  }
  if (only != "env" && only != "clouds") {
    std::vector<Case> cases;
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
    for (double gap : {1.0, 1e-2, 1e-4}) {
      char name[32];
      std::snprintf(name, sizeof name, "sep %g", gap);
      cases.push_back({name, Eigen::Isometry3d::Identity(), placeAtGap(*t1, *t20, X, gap)});
    }
    Eigen::Isometry3d linked = X;  // B's tube through A's hole: 0.5 apart all along a circle (torus R=1, r=0.25)
    linked.translation() = Eigen::Vector3d(1.0, 0, 0);
    cases.push_back({"linked", Eigen::Isometry3d::Identity(), linked});
    run("torus_1k/torus_20k", *t1, *t20, cases, 51);
    std::vector<Case> same;
    for (double gap : {1.0, 1e-2, 1e-4}) {
      char name[32];
      std::snprintf(name, sizeof name, "sep %g", gap);
      same.push_back({name, Eigen::Isometry3d::Identity(), placeAtGap(*t20, *t20, X, gap)});
    }
    same.push_back({"linked", Eigen::Isometry3d::Identity(), linked});
    run("torus_20k/torus_20k", *t20, *t20, same, 51);
    std::vector<Case> small;
    for (double gap : {1.0, 1e-2, 1e-4}) {
      char name[32];
      std::snprintf(name, sizeof name, "sep %g", gap);
      small.push_back({name, Eigen::Isometry3d::Identity(), placeAtGap(*t1, *t1, X, gap)});
    }
    run("torus_1k/torus_1k", *t1, *t1, small, 101);
  }
  if (only != "tori" && only != "clouds") {
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> u(-3000, 3000);
    std::normal_distribution<double> n01;
    std::vector<Case> cases;
    while (cases.size() < 6) {
      Eigen::Isometry3d Xb = Eigen::Isometry3d::Identity();
      Xb.linear() = Eigen::Quaterniond(n01(rng), n01(rng), n01(rng), n01(rng)).normalized().toRotationMatrix();
      Xb.translation() = Eigen::Vector3d(u(rng), u(rng), u(rng));
      const unidist::DistanceResult r = unidist::distance(*env, Eigen::Isometry3d::Identity(), *rob, Xb);
      if (r.distance <= 0) continue;
      cases.push_back({"pose " + std::to_string(cases.size()), Eigen::Isometry3d::Identity(), Xb});
    }
    run("env/rob", *env, *rob, cases, 101);
  }
  if (only != "tori" && only != "env") {
    // Mesh–cloud and cloud–cloud (no FCL counterpart here): ours only, against a brute-force check.
    const auto cloud = unidist::loadModel(models + "/torus_cloud.xyz");
    const auto* pc = dynamic_cast<const unidist::PointCloud*>(cloud.get());
    if (!pc) throw std::runtime_error("torus_cloud.xyz is not a cloud");
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
    for (double shift : {3.0, 2.51, 1.0}) {
      X.translation() = Eigen::Vector3d(shift, 0, 0);
      for (int kind = 0; kind < 2; ++kind) {
        const unidist::Model& a = kind == 0 ? static_cast<const unidist::Model&>(*t20) : *pc;
        const unidist::DistanceResult r = unidist::distance(a, Eigen::Isometry3d::Identity(), *pc, X);
        double brute = std::numeric_limits<double>::infinity();
        if (kind == 1)
          for (const auto& p : pc->points())
            for (const auto& q : pc->points()) brute = std::min(brute, (p - X * q).norm());
        else
          for (const auto& q : pc->points()) brute = std::min(brute, std::abs(t20->closestPoint(X * q).signedDistance));
        const double t = medianMicros(51, [&] { (void)unidist::distance(a, Eigen::Isometry3d::Identity(), *pc, X); });
        std::printf("%-22s shift %-5g ours %.12g [%s, %s, %d node pairs]  brute %.12g  |  median us: ours %.1f\n",
                    kind == 0 ? "torus_20k/torus_cloud" : "torus_cloud/torus_cloud", shift, r.distance,
                    toString(r.status), r.method, r.iterations, brute, t);
      }
    }
  }
  return 0;
}
