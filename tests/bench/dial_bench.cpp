// The tolerance dial (issue 8): for each of the ten pair families (tests/core/dial_families.h: fixed poses, exact
// truths), our distance at requested tolerances 1e-1 … 1e-12 of the model size — median and p90 time, largest
// and median true error, median bound width, share certified — and the peers installed here on the same inputs,
// each at the settings of its own dial (dial_peers.h). One CSV on stdout (docs/results/dial.csv), progress and any
// broken promise (a bound that excludes the truth, a certified answer off by more than its tolerance) on stderr.
// usage: unidist_bench_dial [family|all] [poses-per-kind]
//        unidist_bench_dial compute [poses-per-kind]   what each DistanceOptions::compute costs (apart and
//        penetrating cases apart), at tolerance 1e-6 × size, and whether every overlap verdict was right
#include "bench/dial_peers.h"
#include "bench/dial_stats.h"
#include "core/dial_families.h"

#include <cstdio>
#include <cstdlib>
#include <string>

namespace {

using dial::Case;
using dial::Sample;

/// Our answers at one tolerance on every case of a family; promises broken are reported on stderr. With
/// `atDetail`, both models are asked at the level of detail `relative` × size too (their stand-ins and their
/// structures built before the timing, like every other lazily built structure).
std::vector<Sample> sweepOurs(const dial::Family& f, double relative, int& broken, bool atDetail = false) {
  std::vector<Sample> out;
  double slowestBuild = 0, largestDeviation = 0;  // stand-ins: first build (ms), deviation of a pair / size
  for (const Case& c : f.cases) {
    unidist::DistanceOptions options;
    options.tolerance = relative * c.size;
    if (atDetail) {
      options.detailA = options.detailB = relative * c.size;
      const auto t0 = dial::Clock::now();
      const unidist::StandIn sa = c.a->model->atDetail(options.detailA), sb = c.b->model->atDetail(options.detailB);
      sa.model->buildStructures();  // the stand-ins' hierarchies too: build time is not query time
      sb.model->buildStructures();
      const double deviation = sa.deviation + sb.deviation;
      slowestBuild = std::max(slowestBuild, std::chrono::duration<double, std::milli>(dial::Clock::now() - t0).count());
      largestDeviation = std::max(largestDeviation, deviation / c.size);
    }
    unidist::DistanceResult r;
    Sample s;
    s.micros = dial::medianMicros([&] { return unidist::distance(*c.a->model, c.Xa, *c.b->model, c.Xb, options); }, r);
    s.error = std::abs(r.distance - c.truth) / c.size;
    s.width = (r.upperBound - r.lowerBound) / c.size;
    s.certified = r.status == unidist::Status::Certified;
    const double rounding = 1e-13 * c.size;
    const bool boundsHold = r.lowerBound <= c.truth + rounding && c.truth <= r.upperBound + rounding;
    const bool withinTolerance = !s.certified || std::abs(r.distance - c.truth) <= options.tolerance + rounding;
    if (!boundsHold || !withinTolerance) {
      ++broken;
      std::fprintf(stderr, "  BROKEN %s %s tol %.0e: distance %.17g truth %.17g bounds [%.17g, %.17g] %s (%s)\n",
                   f.name.c_str(), c.what.c_str(), relative, r.distance, c.truth, r.lowerBound, r.upperBound,
                   unidist::toString(r.status), r.method);
    }
    out.push_back(s);
    dial::traceAnswer(f.name, "unidist", c.what + (s.certified ? "" : " (bounded)"), relative, r.distance, c.truth, s.micros);
  }
  if (atDetail)
    std::fprintf(stderr, "  %s level of detail %.0e: stand-ins and their structures built in at most %.1f ms, deviations up to %.3g of the size\n",
                 f.name.c_str(), relative, slowestBuild, largestDeviation);
  return out;
}

/// One CSV row per (family, compute kind): median µs over the apart and the penetrating cases, and how many
/// overlap verdicts (r.overlapping()) disagreed with the truth's sign.
void sweepComputeKinds(const dial::Family& f) {
  using unidist::Compute;
  for (Compute kind : {Compute::Overlap, Compute::Separation, Compute::SignedDistance}) {
    std::vector<double> apart, penetrating;
    int wrong = 0;
    double apartError = 0;  // largest |distance − truth| / size over the apart cases
    for (const Case& c : f.cases) {
      unidist::DistanceOptions options;
      options.tolerance = 1e-6 * c.size;
      options.compute = kind;
      unidist::DistanceResult r;
      const double us =
          dial::medianMicros([&] { return unidist::distance(*c.a->model, c.Xa, *c.b->model, c.Xb, options); }, r);
      (c.truth > 0 ? apart : penetrating).push_back(us);
      if (c.truth > 0) apartError = std::max(apartError, std::abs(r.distance - c.truth) / c.size);
      wrong += std::abs(c.truth) > options.tolerance && r.overlapping() != (c.truth < 0);
    }
    std::printf("%s,%s,%zu,%.4g,%.3g,%zu,%.4g,%d\n", f.name.c_str(), unidist::toString(kind), apart.size(),
                dial::quantile(apart, 0.5), apartError, penetrating.size(), dial::quantile(penetrating, 0.5), wrong);
    std::fflush(stdout);
  }
}

}  // namespace

int main(int argc, char** argv) {
  const std::string only = argc > 1 ? argv[1] : "all";
  const int perKind = argc > 2 ? std::atoi(argv[2]) : 3;
  const dial::Library library;
  if (only == "compute") {
    std::printf("family,compute,apart_cases,apart_median_us,apart_max_error,penetrating_cases,penetrating_median_us,wrong_verdicts\n");
    for (const dial::FamilyBuilder& builder : dial::familyBuilders()) {
      const dial::Family f = builder.build(library, perKind);
      for (const Case& c : f.cases) (void)unidist::distance(*c.a->model, c.Xa, *c.b->model, c.Xb);  // lazy builds
      sweepComputeKinds(f);
    }
    return 0;
  }
  dial::printHeader();
  int broken = 0;
  for (const dial::FamilyBuilder& builder : dial::familyBuilders()) {
    if (only != "all" && only != builder.name) continue;
    const auto t0 = dial::Clock::now();
    const dial::Family f = builder.build(library, perKind);
    int penetrating = 0;
    for (const Case& c : f.cases) penetrating += c.penetrating;
    std::fprintf(stderr, "%s: %zu cases (%d penetrating), truths in %.1f s\n", f.name.c_str(), f.cases.size(),
                 penetrating, std::chrono::duration<double>(dial::Clock::now() - t0).count());
    for (const Case& c : f.cases) (void)unidist::distance(*c.a->model, c.Xa, *c.b->model, c.Xb);  // lazy builds
    for (double relative : dial::decades()) dial::printRow(f.name, "unidist", relative, sweepOurs(f, relative, broken), true);
    // The level of detail: NURBS tessellations and decimated clouds standing in, at 1e-1 … 1e-4 of the size.
    if (f.name.find("nurbs") != std::string::npos || f.name.find("cloud") != std::string::npos)
      for (double relative : {1e-1, 1e-2, 1e-3, 1e-4})
        dial::printRow(f.name, "unidist level of detail", relative, sweepOurs(f, relative, broken, true), true);
    dial::runPeers(f);
    std::fprintf(stderr, "%s: done in %.1f s\n", f.name.c_str(), std::chrono::duration<double>(dial::Clock::now() - t0).count());
  }
  std::fprintf(stderr, "broken promises: %d\n", broken);
  return 0;
}
