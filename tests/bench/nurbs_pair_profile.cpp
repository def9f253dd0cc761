// One surface–surface placement of nurbs_truth.h, ours only (no OpenCASCADE): for profiling and counting
// instructions: valgrind --tool=callgrind --toggle-collect='*timedQueries*' counts the timed queries only (the
// first query, which builds the cached trees, is outside).
// usage: unidist_bench_nurbs_pair_profile [placement name or part of names] [repetitions] [tolerance] [primitive]
// prints per placement: the CPU time per query (median), the value, status, bounds and iterations. With
// "primitive" A is also the analytic torus primitive (the same torus): the route through its exact NURBS form,
// beside the analytic routines (torus–torus circle search, sphere–torus) on the same placement.
#include "bench/median.h"
#include "bench/nurbs_truth.h"

#include "unidist/distance.h"
#include "unidist/primitives.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
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

}  // namespace

int main(int argc, char** argv) {
  const std::string filter = argc > 1 ? argv[1] : "";
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
