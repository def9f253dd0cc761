// Contact search cost: unidist::contacts on FCL's env/rob meshes and the acceptance tori, with the number of
// contacts found. Each case is timed over repeated calls (median), hierarchies built beforehand (the per-query
// adjacency and widened cones are lazy and included).
// Usage: unidist_bench_contacts <acceptance models dir> <fcl data dir>
#include "unidist/adapters/load.h"
#include "unidist/contacts.h"
#include "unidist/distance.h"
#include "unidist/mesh.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace {

using unidist::TriangleMesh;
using Iso = Eigen::Isometry3d;

std::shared_ptr<const TriangleMesh> loadMesh(const std::string& path) {
  auto m = std::dynamic_pointer_cast<const TriangleMesh>(unidist::loadModel(path));
  if (!m) throw std::runtime_error(path + " is not a mesh");
  m->bvh();  // built outside the timing
  return m;
}

/// Median wall time of fn in microseconds (repeated until ~0.2 s or 400 runs).
double medianMicros(const std::function<void()>& fn) {
  std::vector<double> t;
  const auto begin = std::chrono::steady_clock::now();
  const auto budget = std::chrono::milliseconds(200);
  while (t.size() < 400 && (t.size() < 5 || std::chrono::steady_clock::now() - begin < budget)) {
    const auto s = std::chrono::steady_clock::now();
    fn();
    t.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - s).count());
  }
  std::nth_element(t.begin(), t.begin() + t.size() / 2, t.end());
  return t[t.size() / 2];
}

void report(const char* label, const std::string& which, const TriangleMesh& a, const TriangleMesh& b, const Iso& Xb,
            double margin) {
  unidist::ContactOptions o;
  o.margin = margin;
  std::size_t count = 0;
  double deepest = 0;
  const double us = medianMicros([&] {
    const auto cs = unidist::contacts(a, Iso::Identity(), b, Xb, o);
    count = cs.size();
    deepest = cs.empty() ? NAN : cs.front().distance;
  });
  o.maxContacts = 4;
  const double us4 = medianMicros([&] { (void)unidist::contacts(a, Iso::Identity(), b, Xb, o); });
  std::printf("%-22s %-18s margin %-10.4g contacts %5zu  deepest %-12.5g %10.1f us  (max 4: %.1f us)\n", label,
              which.c_str(), margin, count, deepest, us, us4);
}

/// B's translation along x so that the distance is about `gap` (bisection on the distance, outside the timing).
Iso placeAtGap(const TriangleMesh& a, const TriangleMesh& b, Iso Xb, double gap) {
  double lo = 0, hi = 10 * (a.localBounds().diagonal() + b.localBounds().diagonal());
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    Xb.translation().x() = mid;
    const double d = unidist::distance(a, Iso::Identity(), b, Xb).distance;
    (d < gap ? lo : hi) = mid;
    if (std::abs(d - gap) < 1e-3 * gap) break;
  }
  return Xb;
}

void tori(const char* label, const TriangleMesh& a, const TriangleMesh& b) {
  Iso X = Iso::Identity();
  X.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  for (double gap : {1e-2, 1e-4}) {
    const Iso Xb = placeAtGap(a, b, X, gap);
    report(label, "gap " + std::to_string(gap).substr(0, 6), a, b, Xb, 2 * gap);
    Iso over = Xb;
    over.translation().x() -= 2 * gap;  // now overlapping by about gap
    report(label, "overlap ~" + std::to_string(gap).substr(0, 6), a, b, over, 0);
  }
  Iso linked = X;  // B's tube through A's hole, 0.5 apart along a whole circle
  linked.translation() = Eigen::Vector3d(1.0, 0, 0);
  report(label, "linked", a, b, linked, 0.55);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s <acceptance models dir> <fcl data dir>\n", argv[0]);
    return 2;
  }
  const std::string models = argv[1], fcl = argv[2];
  const auto t1 = loadMesh(models + "/torus_1k.obj"), t20 = loadMesh(models + "/torus_20k.obj");
  const auto env = loadMesh(fcl + "/env.obj"), rob = loadMesh(fcl + "/rob.obj");

  tori("torus_1k/torus_1k", *t1, *t1);
  tori("torus_1k/torus_20k", *t1, *t20);
  tori("torus_20k/torus_20k", *t20, *t20);

  // env/rob: FCL's random poses (rob in [-3000, 3000]^3), kept when separated; margin = distance + 1 % of rob.
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-3000, 3000);
  std::normal_distribution<double> n01;
  const double robSize = rob->localBounds().diagonal();
  for (int k = 0; k < 6;) {
    Iso Xb = Iso::Identity();
    Xb.linear() = Eigen::Quaterniond(n01(rng), n01(rng), n01(rng), n01(rng)).normalized().toRotationMatrix();
    Xb.translation() = Eigen::Vector3d(u(rng), u(rng), u(rng));
    const double d = unidist::distance(*env, Iso::Identity(), *rob, Xb).distance;
    if (d <= 0) continue;
    report("env/rob", "pose " + std::to_string(k++), *env, *rob, Xb, d + 0.01 * robSize);
    if (k == 6) break;
  }
  return 0;
}
