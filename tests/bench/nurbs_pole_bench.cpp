// Point queries next to a pole of the exact rational sphere (docs/nurbs.md, "Strips along poles"): per band of
// distance from the pole, how many error bounds exceed twice the tolerance, the worst, the nodes popped and the
// time per query; then random points around the sphere.
// usage: unidist_bench_nurbs_pole [points per band] [relative tolerance]
#include "core/nurbs_fixtures.h"
#include "nurbs/objectives.h"
#include "nurbs/patch_search.h"

#include "unidist/nurbs.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>

namespace {

using Vec = Eigen::Vector3d;
using unidist::nurbs::SearchResult;

struct Tally {
  int wide = 0, premised = 0, missed = 0;
  double worst = 0, seconds = 0;
  long nodes = 0;
};

// One query against the analytic distance: a miss is a value above the truth by more than the error bound, or
// a lower bound above the truth.
void measure(const unidist::NurbsModel& ball, const Vec& q, double size, double tolerance, Tally& t) {
  const auto start = std::chrono::steady_clock::now();
  const SearchResult r = unidist::nurbs::minimise(ball.forest(), ball.patches(),
                                                  unidist::nurbs::PointObjective(q, size), tolerance, 0);
  t.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double truth = std::abs(q.norm() - 1), error = r.best.value - r.lowerBound;
  t.missed += r.lowerBound > truth + 1e-15 || r.best.value > truth + error + 1e-15;
  t.wide += error > 2 * tolerance;
  t.worst = std::max(t.worst, error / size);
  t.premised += r.premised;
  t.nodes += r.nodes;
}

void print(const char* label, const Tally& t, int count) {
  std::printf("%-14s wide %4d  worst %.2e x size  premised %4d  missed %d  nodes/query %6.1f  us/query %7.2f\n", label,
              t.wide, t.worst, t.premised, t.missed, double(t.nodes) / count, 1e6 * t.seconds / count);
}

}  // namespace

int main(int argc, char** argv) {
  const int perBand = argc > 1 ? std::atoi(argv[1]) : 500;
  const double relative = argc > 2 ? std::atof(argv[2]) : 1e-10;
  const unidist::NurbsModel ball({nurbs_fixtures::sphereSurface()}, true);
  const double size = ball.localBounds().diagonal(), tolerance = relative * size;
  ball.closestPoint(Vec(0, 0, 2));  // builds the cached tree's top and the start set outside the timings
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> U(-1, 1);
  std::printf("unit sphere, tolerance %.0e x size, %d points per band (both poles, inside and outside)\n", relative,
              perBand);
  for (int band = -7; band <= 0; ++band) {
    const double spread = std::pow(10.0, band);
    Tally t;
    for (int k = 0; k < perBand; ++k)
      measure(ball, Vec(spread * U(rng), spread * U(rng), (k % 2 ? 1 : -1) * (1 + spread * U(rng))), size, tolerance, t);
    char label[32];
    std::snprintf(label, sizeof label, "within 1e%d", band);
    print(label, t, perBand);
  }
  Tally t;
  const int random = 8 * perBand;
  for (int k = 0; k < random; ++k) measure(ball, Vec(2 * U(rng), 2 * U(rng), 2 * U(rng)), size, tolerance, t);
  print("random", t, random);
}
