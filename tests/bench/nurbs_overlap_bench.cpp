// Penetration depth of the non-convex exact NURBS torus (R = 1, a = 0.25) against a NURBS ball (ρ = 0.4), the sphere
// primitive of the same radius, and a box (half 0.3) lying across the tube's top, by depth band; and two tori
// shifted through each other. Truth: a ball centred at c overlaps the torus by a + ρ − dist(c, core circle); the
// box by how far its face sinks below the tube's top; the tori by the closed forms of nurbs_truth.h (side,
// coaxial) and 0.4 for a shift of 0.1 along the axis. No peer answers these: OpenCASCADE's extrema return 0 for
// crossing surfaces (nurbs_vs_occt), and FCL has no NURBS or non-convex depth.
// usage: unidist_bench_nurbs_overlap [placements per band] [tolerance] [sweep]
// prints per band: the median and maximum CPU time, how many answers are certified, and the worst error. With
// "sweep": the torus in random poses instead, balls sunk 1e-7 to 0.35 (placements per depth), checked against
// the truth: misses, uncertified answers, times.
#include "bench/median.h"
#include "bench/nurbs_truth.h"

#include "unidist/distance.h"
#include "unidist/primitives.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <numeric>
#include <random>
#include <string>
#include <vector>

namespace {

using Vec = Eigen::Vector3d;

double cpuMillis() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

struct Band {
  std::vector<double> ms;
  int certified = 0;
  double worstError = 0;
};

void report(const char* pair, double depth, const Band& b) {
  std::printf("%-26s depth %-7g median %9.2f ms  max %9.2f ms  certified %3d/%-3zu  worst error %.1e\n", pair, depth,
              median(b.ms), quantile(b.ms, 1.0), b.certified, b.ms.size(), b.worstError);
  std::printf("csv,overlap,%s,%g,%.4g,%.4g,%d,%zu,%.3g\n", pair, depth, median(b.ms), quantile(b.ms, 1.0), b.certified,
              b.ms.size(), b.worstError);
}

void measure(Band& band, double truth, const std::function<unidist::DistanceResult()>& query) {
  const double t0 = cpuMillis();
  const unidist::DistanceResult r = query();
  band.ms.push_back(cpuMillis() - t0);
  band.certified += r.status == unidist::Status::Certified;
  band.worstError = std::max(band.worstError, std::abs(r.distance - truth));
}

/// The wide check: the torus in a random pose against the NURBS ball and the sphere primitive sunk at a random
/// place around its tube, `perDepth` placements per depth: how many brackets miss the truth, how many answers are
/// not certified, and the worst time.
void sweep(const unidist::Model& torus, const unidist::Model& ball, const unidist::Model& sphere, double R,
           double reach, int perDepth, const unidist::DistanceOptions& options) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> angle(0, 2 * M_PI), u(-1, 1);
  int total = 0, missed = 0, uncertified = 0;
  std::vector<double> ms;
  for (double depth : {1e-7, 1e-4, 0.01, 0.1, 0.2, 0.3, 0.35})
    for (int k = 0; k < perDepth; ++k) {
      const nurbs_truth::TubePlace place{angle(rng), angle(rng)};
      Eigen::Isometry3d XA = Eigen::Isometry3d::Identity();
      XA.linear() = Eigen::Quaterniond(Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
      XA.translation() = Vec(u(rng), u(rng), u(rng));
      Eigen::Isometry3d XB = XA;
      XB.translation() = XA * place.point(R, reach - depth);
      for (const unidist::Model* b : {&ball, &sphere}) {
        const double t0 = cpuMillis();
        const unidist::DistanceResult r = unidist::distance(torus, XA, *b, XB, options);
        ms.push_back(cpuMillis() - t0);
        ++total;
        missed += !(r.lowerBound <= -depth + 1e-12 && r.upperBound >= -depth - 1e-12);
        uncertified += r.status != unidist::Status::Certified;
      }
    }
  std::printf("sweep: %d placements, brackets missing the truth %d, not certified %d, median %.2f ms, max %.1f ms, "
              "total %.1f s\n", total, missed, uncertified, median(ms), quantile(ms, 1.0),
              1e-3 * std::accumulate(ms.begin(), ms.end(), 0.0));
}

}  // namespace

int main(int argc, char** argv) {
  const int count = argc > 1 ? std::atoi(argv[1]) : 20;
  const double tolerance = argc > 2 ? std::atof(argv[2]) : 1e-9;
  const bool wide = argc > 3 && std::string(argv[3]) == "sweep";
  const double R = 1, a = 0.25, rho = 0.4, half = 0.3;
  const unidist::NurbsModel torus({nurbs_fixtures::torusSurface(R, a)}, true);
  const unidist::NurbsModel ball({nurbs_fixtures::sphereSurface(rho)}, true);
  const unidist::Sphere sphere(rho);
  const unidist::Box box(Vec(half, half, half));
  unidist::DistanceOptions options;
  options.tolerance = tolerance;
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> angle(0, 2 * M_PI);
  std::printf("# tolerance %g, %d placements per band; "
              "csv,overlap,pair,depth,median_ms,max_ms,certified,count,worst_error\n",
              tolerance, count);
  (void)unidist::distance(torus, I, ball, Eigen::Isometry3d(Eigen::Translation3d(2, 0, 0)), options);  // trees built
  if (wide) {
    sweep(torus, ball, sphere, R, a + rho, count, options);
    return 0;
  }
  for (double depth : {1e-6, 1e-3, 0.05, 0.3}) {
    Band nurbsBall, primitive, boxBand;
    for (int k = 0; k < count; ++k) {
      // The ball's centre off the tube at a random place around it; the box's face over the tube's top, turned.
      const nurbs_truth::TubePlace place{angle(rng), angle(rng)};
      const Eigen::Isometry3d X_B(Eigen::Translation3d(place.point(R, a + rho - depth)));
      measure(nurbsBall, -depth, [&] { return unidist::distance(torus, I, ball, X_B, options); });
      measure(primitive, -depth, [&] { return unidist::distance(torus, I, sphere, X_B, options); });
      if (depth >= 0.3) continue;  // a box sunk below the tube's top by more than its radius crosses it elsewhere
      Eigen::Isometry3d X_box = Eigen::Isometry3d::Identity();
      X_box.translate(R * place.radial() + Vec(0, 0, a + half - depth));
      X_box.rotate(Eigen::AngleAxisd(place.around, Vec::UnitZ()));
      measure(boxBand, -depth, [&] { return unidist::distance(torus, I, box, X_box, options); });
    }
    report("torus-NURBS ball", depth, nurbsBall);
    report("torus-sphere primitive", depth, primitive);
    if (!boxBand.ms.empty()) report("torus-box", depth, boxBand);
  }
  for (const nurbs_truth::Placement& p : nurbs_truth::placements()) {
    if (!(p.truth < 0)) continue;
    Band band;
    for (int k = 0; k < std::max(1, count / 4); ++k)
      measure(band, p.truth, [&] { return unidist::distance(torus, I, torus, p.X_WB, options); });
    report(p.name, -p.truth, band);
  }
  Band shifted;
  for (int k = 0; k < std::max(1, count / 4); ++k)
    measure(shifted, -0.4, [&] {
      return unidist::distance(torus, I, torus, Eigen::Isometry3d(Eigen::Translation3d(0, 0, 0.1)), options);
    });
  report("torus-torus shifted 0.1", 0.4, shifted);
  return 0;
}
