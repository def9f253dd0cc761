// One surface–surface placement of nurbs_truth.h, ours only (no OpenCASCADE): for profiling and counting
// instructions: valgrind --tool=callgrind --toggle-collect='*timedQueries*' counts the timed queries only (the
// first query, which builds the cached trees, is outside).
// usage: unidist_bench_nurbs_pair_profile [placement name or part of names] [repetitions] [tolerance] [primitive]
//        unidist_bench_nurbs_pair_profile random [placements per kind] [tolerance]
// prints per placement: the CPU time per query (median), the value, status, bounds and iterations. With
// "primitive" A is also the analytic torus primitive (the same torus): the route through its exact NURBS form,
// beside the analytic routines (torus–torus circle search, sphere–torus) on the same placement. "random": the
// torus against a torus and against a sphere in random separated poses (seeded), each query's best of three
// CPU times, then median, mean and worst per kind, with the answers off the circle truth by more than 1e-8 and
// the uncertified ones: a speed-up of the fixed placements above must hold here too (one that halved
// torus–sphere "above" made the random tori's median 25 % slower).
#include "bench/median.h"
#include "bench/nurbs_truth.h"

#include "unidist/distance.h"
#include "unidist/primitives.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <random>
#include <string>
#include <vector>

namespace {

double cpuMicros() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return 1e6 * static_cast<double>(t.tv_sec) + 1e-3 * static_cast<double>(t.tv_nsec);
}

/// The repeated queries (a function of its own: callgrind's --toggle-collect can count just these).
[[gnu::noinline]] std::vector<double> timedQueries(const unidist::Model& a, const unidist::Model& b,
                                                    const Eigen::Isometry3d& X_WB, const unidist::DistanceOptions& options,
                                                    int reps, unidist::DistanceResult& r) {
  std::vector<double> times;
  for (int k = 0; k < reps; ++k) {
    const double t0 = cpuMicros();
    r = unidist::distance(a, Eigen::Isometry3d::Identity(), b, X_WB, options);
    times.push_back(cpuMicros() - t0);
  }
  return times;
}

/// The placements of the "random" mode: per kind (torus–torus, torus–sphere) `count` separated poses.
void randomPlacements(int count, double tolerance) {
  using Vec = Eigen::Vector3d;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1, 1);
  const double R = 1, a = 0.25, rs = 0.4;  // the fixed placements' torus and sphere
  const unidist::NurbsModel torus({nurbs_fixtures::torusSurface(R, a)}, true);
  const unidist::NurbsModel sphere({nurbs_fixtures::sphereSurface(rs)}, true);
  const nurbs_truth::Circle core{Vec::Zero(), Vec::UnitZ(), R};
  unidist::DistanceOptions options;
  options.tolerance = tolerance;
  for (const bool withSphere : {false, true}) {
    const unidist::Model& b = withSphere ? static_cast<const unidist::Model&>(sphere) : torus;
    std::vector<double> times;
    int wrong = 0, uncertified = 0;
    while (static_cast<int>(times.size()) < count) {
      const Vec t(1.8 * unit(rng), 1.8 * unit(rng), unit(rng)), axis(unit(rng), unit(rng), unit(rng));
      const double angle = 3 * unit(rng);
      if (axis.norm() < 1e-3) continue;
      const Eigen::Isometry3d X = nurbs_truth::pose(t, Eigen::AngleAxisd(angle, axis.normalized()));
      const double truth = withSphere ? nurbs_truth::pointCircle(t, core) - a - rs
                                      : nurbs_truth::circleCircle(core, {t, X.linear() * Vec::UnitZ(), R}) - 2 * a;
      if (truth < 0.01) continue;  // separated placements only: the overlap bench has the others
      unidist::DistanceResult r;
      const std::vector<double> three = timedQueries(torus, b, X, options, 3, r);
      times.push_back(*std::min_element(three.begin(), three.end()));
      wrong += std::abs(r.distance - truth) > 1e-8;
      uncertified += r.status != unidist::Status::Certified;
    }
    double mean = 0;
    for (double x : times) mean += x / static_cast<double>(times.size());
    std::printf("random %-14s %d placements  cpu median %7.1f us  mean %7.1f us  worst %8.1f us  wrong %d  "
                "uncertified %d\n",
                withSphere ? "torus-sphere" : "torus-torus", count, median(times), mean,
                *std::max_element(times.begin(), times.end()), wrong, uncertified);
  }
}

}  // namespace

int main(int argc, char** argv) {
  const std::string filter = argc > 1 ? argv[1] : "";
  if (filter == "random") {
    randomPlacements(argc > 2 ? std::atoi(argv[2]) : 200, argc > 3 ? std::atof(argv[3]) : 1e-9);
    return 0;
  }
  const int reps = argc > 2 ? std::atoi(argv[2]) : 21;
  const double tolerance = argc > 3 ? std::atof(argv[3]) : 1e-9;
  const bool primitive = argc > 4 && std::string(argv[4]) == "primitive";
  const std::vector<nurbs_truth::Placement> placements = nurbs_truth::placements();
  // A whole name selects that placement alone (one name can be the start of another); otherwise a substring.
  const bool exact = std::any_of(placements.begin(), placements.end(), [&](const auto& p) { return filter == p.name; });
  for (const nurbs_truth::Placement& p : placements) {
    if (exact ? filter != p.name : std::string(p.name).find(filter) == std::string::npos) continue;
    const unidist::NurbsModel a({p.a}, true), b({p.b}, true);
    unidist::DistanceOptions options;
    options.tolerance = tolerance;
    const auto run = [&](const char* label, const unidist::Model& ma, const unidist::Model& mb) {
      unidist::DistanceResult r = unidist::distance(ma, Eigen::Isometry3d::Identity(), mb, p.X_WB, options);
      const std::vector<double> times = timedQueries(ma, mb, p.X_WB, options, reps, r);
      std::printf("%-28s %-18s cpu %9.1f us  value %+.12f (truth %+.12f, error %.1e)  bounds [%+.12f, %+.12f]  %s  "
                  "iterations %d  width %.3g  %s\n",
                  p.name, label, median(times), r.distance, p.truth, r.distance - p.truth, r.lowerBound,
                  r.upperBound, unidist::toString(r.status), r.iterations, r.upperBound - r.lowerBound, r.method);
    };
    run("nurbs-nurbs", a, b);
    if (!primitive) continue;
    const unidist::Torus torus(1, 0.25);  // placements' A: the torus R = 1, a = 0.25
    run("torus-prim-nurbs", torus, b);
    const bool torusB = std::string(p.name).rfind("torus-torus", 0) == 0;
    const unidist::Sphere sphere(0.4);  // placements' spheres
    if (torusB) run("analytic", torus, torus);
    else run("analytic", torus, sphere);
  }
  return 0;
}
