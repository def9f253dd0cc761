// The simulation contacts' warm start (unidist/contact_manifold.h) on resting NURBS pairs: per-step cost of
// manifoldContacts() with a ContactCache whose updates project locally (the tracker's point Newton from each
// contact's (u, v), the default), with one that re-projects by the exact search, and without a cache (a fresh
// search every step), on the same poses in the same run. A resting body's pose jitters as an engine's does
// (sinking ~1e-4 of its size, drifting 1e-6 per step, turning 1e-6 rad): the pair stays within the guard most
// of the time. Also the largest difference of the deepest contact's distance from the fresh search's.
// Usage: unidist_bench_warm_start [steps=300]   (CSV on stdout)
#include "unidist/contact_manifold.h"
#include "unidist/mesh.h"
#include "unidist/nurbs.h"
#include "unidist/primitives.h"

#include "bench/median.h"
#include "core/mesh_fixtures.h"
#include "core/nurbs_fixtures.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

namespace {

using Iso = Eigen::Isometry3d;
using Vec = Eigen::Vector3d;

Iso pose(const Vec& t, const Eigen::Quaterniond& q) {
  Iso X = Iso::Identity();
  X.linear() = q.normalized().toRotationMatrix();
  X.translation() = t;
  return X;
}

struct Pair {
  std::string name;
  const unidist::Model& a;
  const unidist::Model& b;
  Iso X_WB;
  double restHeight;  ///< A's centre above B's frame origin when touching
  Eigen::Quaterniond turnA;
};

struct Run {
  std::vector<double> micros;
  std::vector<double> deepest;
  unidist::ContactCache cache;
};

/// Steps the resting jitter through manifoldContacts with the given cache mode (nullptr cache: fresh).
Run run(const Pair& p, int steps, bool useCache, bool local) {
  unidist::ManifoldOptions o;
  o.margin = 0.01;
  o.localWarmStart = local;
  Run r;
  for (int i = 0; i < steps; ++i) {
    const double sink = 1e-4 * (1 + 0.2 * std::sin(0.37 * i));
    const Iso X = pose(Vec(1e-6 * i, 0, p.restHeight - sink),
                       p.turnA * Eigen::Quaterniond(Eigen::AngleAxisd(1e-6 * i, Vec::UnitX())));
    const auto t0 = std::chrono::steady_clock::now();
    const auto cs = unidist::manifoldContacts(p.a, X, p.b, p.X_WB, o, useCache ? &r.cache : nullptr);
    const auto t1 = std::chrono::steady_clock::now();
    r.micros.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
    r.deepest.push_back(cs.empty() ? std::nan("") : cs.front().distance);
  }
  return r;
}

double largestDifference(const std::vector<double>& x, const std::vector<double>& y) {
  double worst = 0;
  for (std::size_t i = 0; i < x.size(); ++i) worst = std::max(worst, std::abs(x[i] - y[i]));
  return worst;
}

}  // namespace

int main(int argc, char** argv) {
  const int steps = argc > 1 ? std::atoi(argv[1]) : 300;
  const unidist::NurbsModel ball({nurbs_fixtures::sphereSurface(0.5)}, true);
  const unidist::NurbsModel torus({nurbs_fixtures::torusSurface(1, 0.25)}, true);
  const unidist::Box table(Vec(2, 2, 0.5));
  const unidist::TriangleMesh meshTable = meshfix::makeMesh(meshfix::gridBox(Vec(2, 2, 0.5), 8));
  meshTable.buildStructures();
  const Eigen::Quaterniond turn(0.9, 0.2, -0.3, 0.25);
  const Eigen::Quaterniond upright(Eigen::AngleAxisd(0.3, Vec::UnitZ()));
  const Iso below = pose(Vec(0, 0, -0.5), Eigen::Quaterniond::Identity());
  const std::vector<Pair> pairs = {
      {"NURBS ball on box", ball, table, below, 0.5, turn},
      {"NURBS torus on box", torus, table, below, 0.25, upright},
      {"NURBS ball on mesh box", ball, meshTable, below, 0.5, turn},
      {"NURBS ball on NURBS ball", ball, ball, pose(Vec::Zero(), turn), 1.0, turn},
  };
  std::printf("pair,steps,fresh_us,warm_exact_us,warm_local_us,exact_over_local,fresh_over_local,global_searches,"
              "local_updates,local_projections,fallbacks,max_deepest_diff_local,max_deepest_diff_exact\n");
  for (const Pair& p : pairs) {
    const Run fresh = run(p, steps, false, true);
    const Run exact = run(p, steps, true, false);
    const Run local = run(p, steps, true, true);
    const double f = median(fresh.micros), e = median(exact.micros), l = median(local.micros);
    std::printf("%s,%d,%.2f,%.2f,%.2f,%.2f,%.2f,%ld,%ld,%ld,%ld,%.3g,%.3g\n", p.name.c_str(), steps, f, e, l, e / l, f / l,
                local.cache.globalSearches, local.cache.localUpdates, local.cache.localProjections,
                local.cache.projectionFallbacks, largestDifference(local.deepest, fresh.deepest),
                largestDifference(exact.deepest, fresh.deepest));
  }
  return 0;
}
