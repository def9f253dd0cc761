// Point queries next to a pole of the exact rational sphere (docs/nurbs.md, "Strips along poles"): per band of
// distance from the pole, how many error bounds exceed twice the tolerance, the worst, the nodes popped and the
// time per query; then random points around the sphere; then the same bands about a pole that is not smooth, an
// open cone's apex.
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
void measure(const unidist::NurbsModel& model, const Vec& q, double truth, double size, double tolerance, Tally& t) {
  const auto start = std::chrono::steady_clock::now();
  const SearchResult r = unidist::nurbs::minimise(model.forest(), model.patches(),
                                                  unidist::nurbs::PointObjective(q, size), tolerance, 0);
  t.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double error = r.best.value - r.lowerBound;
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
    for (int k = 0; k < perBand; ++k) {
      const Vec q(spread * U(rng), spread * U(rng), (k % 2 ? 1 : -1) * (1 + spread * U(rng)));
      measure(ball, q, std::abs(q.norm() - 1), size, tolerance, t);
    }
    char label[32];
    std::snprintf(label, sizeof label, "within 1e%d", band);
    print(label, t, perBand);
  }
  Tally t;
  const int random = 8 * perBand;
  for (int k = 0; k < random; ++k) {
    const Vec q(2 * U(rng), 2 * U(rng), 2 * U(rng));
    measure(ball, q, std::abs(q.norm() - 1), size, tolerance, t);
  }
  print("random", t, random);

  // The open cone z = 1 − r (r <= 1) as a surface of revolution, its apex (0, 0, 1) a corner of every patch.
  using nurbs_fixtures::Point2W;
  const std::vector<Point2W> profile = {{0, 1, 1}, {0.5, 0.5, 1}, {1, 0, 1}};
  const unidist::NurbsModel cone({unidist::NurbsSurface{2, 2, nurbs_fixtures::circleKnots(), {0, 0, 0, 1, 1, 1},
                                                        nurbs_fixtures::revolve(profile, 1, Vec::Zero())}},
                                 false);
  const auto toCone = [](const Vec& q) {  // the distance to the profile segment from (0, 1) to (1, 0)
    const Eigen::Vector2d p(std::hypot(q.x(), q.y()), q.z()), a(0, 1), b(1, 0);
    const double s = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    return (p - a - s * (b - a)).norm();
  };
  const double coneSize = cone.localBounds().diagonal();
  cone.closestPoint(Vec(0, 0, 2));
  std::printf("open cone, tolerance %.0e x size, %d points per band about its apex\n", relative, perBand);
  for (int band = -7; band <= 0; ++band) {
    const double spread = std::pow(10.0, band);
    Tally c;
    for (int k = 0; k < perBand; ++k) {
      const Vec q(spread * U(rng), spread * U(rng), 1 + spread * U(rng));
      measure(cone, q, toCone(q), coneSize, relative * coneSize, c);
    }
    char label[32];
    std::snprintf(label, sizeof label, "within 1e%d", band);
    print(label, c, perBand);
  }
}
