// Meshes: unidist against FCL 0.7's BVHModel<OBBRSS> and <RSS>, same meshes and poses, same run. Groups:
//   build   hierarchy build: ours (BVH alone, and with the RSS node volumes mesh–mesh queries fit on first use)
//           against FCL's model build
//   tori    mesh–mesh separation: tori of ~1k, ~10k, ~100k triangles (generated) and the acceptance 1k/20k
//           tori, at gaps 1, 1e-2, 1e-4 and linked (tube through the other's hole, 0.5 apart along a circle)
//   env     FCL's own benchmark room and robot at random separated poses
//   points  point → mesh: our closestPoint against FCL's distance to a sphere of radius 0
//   clouds  mesh–cloud and cloud–cloud (no FCL counterpart): ours against brute force
//   linked  only the linked tori (for quick measurements; not part of the full run)
// Every line is printed for people and again as a "csv," line (columns in the header lines). A query line
// is OK when our answer is certified and within 1e-9 relative of FCL's. Usage:
//   unidist_bench_mesh_vs_fcl [models dir] [fcl data dir] [build|tori|env|points|clouds|linked]
#include "mesh/bvh.h"
#include "mesh_vs_fcl_util.h"
#include "unidist/adapters/load.h"
#include "unidist/distance.h"
#include "unidist/point_cloud.h"

#include <algorithm>
#include <cstdio>
#include <random>
#include <string>

namespace {

using bench::medianMicros;
using unidist::TriangleMesh;

struct Case {
  std::string name;
  Eigen::Isometry3d Xa, Xb;
};

void queries(const std::string& label, const TriangleMesh& a, const TriangleMesh& b, const std::vector<Case>& cases) {
  const auto oa = bench::fclMesh<fcl::OBBRSSd>(a), ob = bench::fclMesh<fcl::OBBRSSd>(b);
  const auto ra = bench::fclMesh<fcl::RSSd>(a), rb = bench::fclMesh<fcl::RSSd>(b);
  (void)unidist::distance(a, Eigen::Isometry3d::Identity(), b, Eigen::Isometry3d::Identity());  // build ours
  for (const Case& c : cases) {
    const unidist::DistanceResult r = unidist::distance(a, c.Xa, b, c.Xb);
    const double fo = bench::fclDistance(oa.get(), c.Xa, ob.get(), c.Xb);
    const double fr = bench::fclDistance(ra.get(), c.Xa, rb.get(), c.Xb);
    const double tOurs = medianMicros(101, [&] { (void)unidist::distance(a, c.Xa, b, c.Xb); });
    const double tObb = medianMicros(101, [&] { (void)bench::fclDistance(oa.get(), c.Xa, ob.get(), c.Xb); });
    const double tRss = medianMicros(101, [&] { (void)bench::fclDistance(ra.get(), c.Xa, rb.get(), c.Xb); });
    const double rel = std::max(std::abs(r.distance - fo), std::abs(r.distance - fr)) / std::max(1e-300, std::abs(fo));
    const bool ok = r.status == unidist::Status::Certified && rel <= 1e-9;
    const double ratio = tOurs / std::min(tObb, tRss);
    std::printf("%-20s %-9s d %.12g [%s, %d node pairs] fcl %.12g rel %.1e %s | median us: ours %.1f obbrss %.1f "
                "rss %.1f ratio %.3f\n",
                label.c_str(), c.name.c_str(), r.distance, toString(r.status), r.iterations, fo, rel, ok ? "OK" : "FAIL",
                tOurs, tObb, tRss, ratio);
    std::printf("csv,%s,%s,%zu,%zu,%.17g,%.17g,%.2e,%s,%d,%.2f,%.2f,%.2f,%.4f\n", label.c_str(), c.name.c_str(),
                a.triangles().size(), b.triangles().size(), r.distance, fo, rel, ok ? "OK" : "FAIL", r.iterations,
                tOurs, tObb, tRss, ratio);
  }
}

/// B's translation along x so that the distance is about `gap` (bisection on our distance, outside the timing).
Eigen::Isometry3d placeAtGap(const TriangleMesh& a, const TriangleMesh& b, Eigen::Isometry3d Xb, double gap) {
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

void toriGroup(const std::string& label, const TriangleMesh& a, const TriangleMesh& b, bool linkedOnly = false) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  std::vector<Case> cases;
  for (double gap : {1.0, 1e-2, 1e-4}) {
    if (linkedOnly) break;
    char name[32];
    std::snprintf(name, sizeof name, "sep %g", gap);
    cases.push_back({name, Eigen::Isometry3d::Identity(), placeAtGap(a, b, X, gap)});
  }
  Eigen::Isometry3d linked = X;  // B's tube through A's hole (both R = 1, r = 0.25)
  linked.translation() = Eigen::Vector3d(1.0, 0, 0);
  cases.push_back({"linked", Eigen::Isometry3d::Identity(), linked});
  queries(label, a, b, cases);
}

void buildTimes(const std::string& label, const TriangleMesh& m) {
  const auto fresh = [&] { return std::make_unique<TriangleMesh>(m.vertices(), m.triangles()); };
  // Each sample builds a batch of fresh meshes (made before the clock starts) so that the CPU clock's own cost
  // (medianMicros) stays out of the small meshes' times.
  const auto t = bench::Clock::now();
  (void)fresh()->bvh();
  const int batch = bench::batchFor(std::chrono::duration<double, std::micro>(bench::Clock::now() - t).count(), 200);
  std::vector<double> bvh, all;
  for (int i = 0; i < 21; ++i) {  // as many samples as FCL's builds get below
    std::vector<std::unique_ptr<TriangleMesh>> meshes;
    for (int k = 0; k < batch; ++k) meshes.push_back(fresh());
    const auto t0 = bench::Clock::now();
    for (const auto& f : meshes) (void)f->bvh();
    const auto t1 = bench::Clock::now();
    for (const auto& f : meshes) (void)f->bvh().rss(f->vertices(), f->triangles());
    const auto t2 = bench::Clock::now();
    bvh.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count() / batch);
    all.push_back(std::chrono::duration<double, std::milli>(t2 - t0).count() / batch);
  }
  std::sort(bvh.begin(), bvh.end());
  std::sort(all.begin(), all.end());
  const double tObb = medianMicros(21, [&] { (void)bench::fclMesh<fcl::OBBRSSd>(m); }) / 1000;
  const double tRss = medianMicros(21, [&] { (void)bench::fclMesh<fcl::RSSd>(m); }) / 1000;
  const double best = std::min(tObb, tRss);
  std::printf("%-20s build %zu triangles  median ms: ours bvh %.3f, bvh+rss %.3f  fcl obbrss %.3f  rss %.3f  "
              "(fcl/ours %.1fx, with rss %.1fx)\n",
              label.c_str(), m.triangles().size(), bvh[10], all[10], tObb, tRss, best / bvh[10], best / all[10]);
  std::printf("csv,build,%s,%zu,%.4f,%.4f,%.4f,%.4f,%.2f,%.2f\n", label.c_str(), m.triangles().size(), bvh[10],
              all[10], tObb, tRss, best / bvh[10], best / all[10]);
}

/// Point → mesh: points within 2 % of the size from the surface ("near") and uniform in the box grown by
/// its size ("far"). Median over the points of one query's time.
void pointQueries(const std::string& label, const TriangleMesh& m) {
  const auto fo = bench::fclMesh<fcl::OBBRSSd>(m);
  const auto fr = bench::fclMesh<fcl::RSSd>(m);
  const auto point = std::make_shared<fcl::Sphered>(0.0);
  (void)m.closestPoint(Eigen::Vector3d::Zero());  // build ours
  const unidist::Aabb box = m.localBounds();
  const double size = box.diagonal();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1), v(-1, 1);
  for (const char* kind : {"near", "far"}) {
    std::vector<Eigen::Vector3d> pts;
    while (pts.size() < 2000) {
      const Eigen::Vector3d q = box.min - 0.5 * size * Eigen::Vector3d::Ones() +
                                (box.max - box.min + size * Eigen::Vector3d::Ones()).cwiseProduct(
                                    Eigen::Vector3d(u(rng), u(rng), u(rng)));
      if (kind[0] == 'f') {
        pts.push_back(q);
        continue;
      }
      const unidist::SurfacePoint s = m.closestPoint(q);
      pts.push_back(s.point + 0.02 * size * v(rng) * s.normal);
    }
    std::vector<double> ours, obb, rss;
    double worst = 0;
    for (const Eigen::Vector3d& q : pts) {
      Eigen::Isometry3d Xq = Eigen::Isometry3d::Identity();
      Xq.translation() = q;
      const double d = std::abs(m.closestPoint(q).signedDistance);
      const double f = bench::fclDistance(fo.get(), Eigen::Isometry3d::Identity(), point.get(), Xq);
      worst = std::max(worst, std::abs(d - f) / std::max(1e-300, f));
      ours.push_back(medianMicros(5, [&] { (void)m.closestPoint(q); }));
      obb.push_back(medianMicros(5, [&] { (void)bench::fclDistance(fo.get(), Eigen::Isometry3d::Identity(), point.get(), Xq); }));
      rss.push_back(medianMicros(5, [&] { (void)bench::fclDistance(fr.get(), Eigen::Isometry3d::Identity(), point.get(), Xq); }));
    }
    const auto median = [](std::vector<double>& t) {
      std::nth_element(t.begin(), t.begin() + t.size() / 2, t.end());
      return t[t.size() / 2];
    };
    const double a = median(ours), b = median(obb), c = median(rss);
    std::printf("%-20s point %-4s %zu triangles  max rel diff %.1e | median us: ours %.2f obbrss %.2f rss %.2f ratio %.3f\n",
                label.c_str(), kind, m.triangles().size(), worst, a, b, c, a / std::min(b, c));
    std::printf("csv,point,%s,%s,%zu,%.2e,%.3f,%.3f,%.3f,%.4f\n", label.c_str(), kind, m.triangles().size(), worst, a, b,
                c, a / std::min(b, c));
  }
}

}  // namespace

void cloudGroup(const std::string& models, const TriangleMesh& t20);  // mesh_vs_fcl_clouds.cpp

int main(int argc, char** argv) {
  const std::string models = argc > 1 ? argv[1] : "/work/shared/acceptance/models";
  const std::string fclData = argc > 2 ? argv[2] : "/work/shared/data/fcl";
  const std::string only = argc > 3 ? argv[3] : "";
  const auto want = [&](const char* g) { return only.empty() || only == g; };
  auto mesh = [](const std::string& path) {
    auto m = std::dynamic_pointer_cast<const TriangleMesh>(unidist::loadModel(path));
    if (!m) throw std::runtime_error(path + " is not a mesh");
    return m;
  };
  const auto t1 = mesh(models + "/torus_1k.obj"), t20 = mesh(models + "/torus_20k.obj");
  const auto env = mesh(fclData + "/env.obj"), rob = mesh(fclData + "/rob.obj");
  const auto g1 = bench::torus(1.0, 0.25, 32, 16), g10 = bench::torus(1.0, 0.25, 100, 50),
             g100 = bench::torus(1.0, 0.25, 316, 158);
  if (want("build")) {
    std::printf("# csv,build,mesh,triangles,ours_bvh_ms,ours_bvh_rss_ms,fcl_obbrss_ms,fcl_rss_ms,fcl_over_ours,fcl_over_ours_with_rss\n");
    for (const auto& [name, m] : {std::pair<const char*, const TriangleMesh*>{"torus 1k", g1.get()},
                                  {"torus 10k", g10.get()}, {"torus 100k", g100.get()}, {"torus_20k.obj", t20.get()},
                                  {"env", env.get()}, {"rob", rob.get()}})
      buildTimes(name, *m);
  }
  if (want("tori")) {
    std::printf("# csv,pair,case,triangles_a,triangles_b,ours,fcl_obbrss,rel_diff,check,node_pairs,ours_us,fcl_obbrss_us,fcl_rss_us,ratio\n");
    toriGroup("torus 1k/1k", *g1, *g1);
    toriGroup("torus 10k/10k", *g10, *g10);
    toriGroup("torus 100k/100k", *g100, *g100);
    toriGroup("torus_1k/torus_20k", *t1, *t20);
    toriGroup("torus_20k/torus_20k", *t20, *t20);
  }
  if (only == "linked") {  // the hardest cases alone (not in the default run)
    toriGroup("torus 1k/1k", *g1, *g1, true);
    toriGroup("torus 10k/10k", *g10, *g10, true);
    toriGroup("torus 100k/100k", *g100, *g100, true);
    toriGroup("torus_1k/torus_20k", *t1, *t20, true);
    toriGroup("torus_20k/torus_20k", *t20, *t20, true);
  }
  if (want("env")) {
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> u(-3000, 3000);
    std::normal_distribution<double> n01;
    std::vector<Case> cases;
    while (cases.size() < 8) {
      Eigen::Isometry3d Xb = Eigen::Isometry3d::Identity();
      Xb.linear() = Eigen::Quaterniond(n01(rng), n01(rng), n01(rng), n01(rng)).normalized().toRotationMatrix();
      Xb.translation() = Eigen::Vector3d(u(rng), u(rng), u(rng));
      if (unidist::distance(*env, Eigen::Isometry3d::Identity(), *rob, Xb).distance <= 0) continue;
      cases.push_back({"pose " + std::to_string(cases.size()), Eigen::Isometry3d::Identity(), Xb});
    }
    queries("env/rob", *env, *rob, cases);
  }
  if (want("points")) {
    std::printf("# csv,point,mesh,kind,triangles,max_rel_diff,ours_us,fcl_obbrss_us,fcl_rss_us,ratio\n");
    pointQueries("torus 1k", *g1);
    pointQueries("torus 10k", *g10);
    pointQueries("torus 100k", *g100);
    pointQueries("env", *env);
  }
  if (want("clouds")) cloudGroup(models, *t20);
  return 0;
}
