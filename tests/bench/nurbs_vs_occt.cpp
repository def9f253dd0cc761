// NURBS queries beside OpenCASCADE 7.6 on the same surfaces, in the same run (docs/nurbs.md).
// usage: unidist_bench_nurbs_vs_occt points|pairs|tolerance [queries-per-model]
//  points:    point projection on an exact rational torus, sphere and a wavy bicubic patch: ours (closestPoint)
//             against GeomAPI_ProjectPointOnSurf prepared once per surface (Grad, Tree, Tree with the MIN flag);
//             per-query medians and misses against the truth (analytic, or grid + Newton for the patch).
//  pairs:     surface–surface minimum distance of tori and spheres in several placements: ours (distance at
//             1e-9) against GeomAPI_ExtremaSurfaceSurface and BRepExtrema_DistShapeShape; exact truth from
//             the distance between the tubes' core circles.
//  tolerance: our time, error and bound width against the tolerance (1e-1 … 1e-12 of the size), per placement.
// Every line starting "csv," is machine-readable (tests/bench/run_nurbs_benchmarks.sh collects them).
#include "bench/median.h"
#include "bench/nurbs_truth.h"
#include "bench/occt_surface.h"
#include "core/nurbs_fixtures.h"
#include "core/nurbs_oracle.h"

#include "unidist/distance.h"

#include <BRepExtrema_DistShapeShape.hxx>
#include <GeomAPI_ExtremaSurfaceSurface.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <random>
#include <string>

namespace {

using Clock = std::chrono::steady_clock;
using Vec = Eigen::Vector3d;
using nurbs_truth::Placement;

double micros(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double, std::micro>(b - a).count(); }

/// Median wall time of `reps` calls (µs); the last call's value is kept in `value`.
double timeMedian(int reps, const std::function<double()>& call, double& value) {
  std::vector<double> t;
  for (int k = 0; k < reps; ++k) {
    const auto a = Clock::now();
    value = call();
    t.push_back(micros(a, Clock::now()));
  }
  return quantile(t, 0.5);
}

// ---- point projection ---------------------------------------------------------------------------------------

struct PointModel {
  std::string name;
  unidist::NurbsSurface surface;
  bool solid;
  std::function<Vec(std::mt19937&)> sample;     // query distribution
  std::function<double(const Vec&)> truth;      // unsigned distance (nullptr: grid oracle)
};

struct Tally {
  std::vector<double> times;
  int misses = 0, noAnswer = 0;
  int interiorMisses = 0;  // misses where the closest point is inside the surface's parameter domain
};

void report(const std::string& model, const char* method, const Tally& t) {
  std::printf("  %-22s median %8.2f us  p90 %8.2f us  max %9.1f us  misses %5d (interior %5d)  no answer %5d\n",
              method, quantile(t.times, 0.5), quantile(t.times, 0.9), quantile(t.times, 1.0), t.misses, t.interiorMisses,
              t.noAnswer);
  std::printf("csv,point,%s,%s,%zu,%.4g,%.4g,%.4g,%d,%d,%d\n", model.c_str(), method, t.times.size(),
              quantile(t.times, 0.5), quantile(t.times, 0.9), quantile(t.times, 1.0), t.misses, t.interiorMisses,
              t.noAnswer);
}

void runPoints(int count) {
  const double kMiss = 1e-9;  // a miss: more than this (× size ~1) above the true distance
  std::uniform_real_distribution<double> U(-1, 1);
  std::vector<PointModel> models;
  models.push_back({"torus", nurbs_fixtures::torusSurface(1, 0.25), true,
                    [U](std::mt19937& r) mutable { return Vec(1.6 * U(r), 1.6 * U(r), 0.6 * U(r)); },
                    [](const Vec& q) { return std::abs(std::hypot(std::hypot(q.x(), q.y()) - 1, q.z()) - 0.25); }});
  models.push_back({"sphere", nurbs_fixtures::sphereSurface(1), true,
                    [U](std::mt19937& r) mutable { return Vec(2 * U(r), 2 * U(r), 2 * U(r)); },
                    [](const Vec& q) { return std::abs(q.norm() - 1); }});
  models.push_back({"wavy patch", nurbs_fixtures::wavySurface(), false,
                    [U](std::mt19937& r) mutable { return Vec(1.6 * U(r), 1.6 * U(r), 0.64 * U(r)); }, nullptr});
  std::printf("# csv,point,model,method,queries,median_us,p90_us,max_us,misses,interior_misses,no_answer\n");
  for (const PointModel& m : models) {
    std::mt19937 rng(11);
    std::vector<Vec> qs;
    for (int k = 0; k < count; ++k) qs.push_back(m.sample(rng));
    std::vector<double> truth;
    if (m.truth) {
      for (const Vec& q : qs) truth.push_back(m.truth(q));
    } else {
      const nurbs_fixtures::GridOracle oracle(m.surface);
      for (const Vec& q : qs) truth.push_back(oracle.distance(q));
    }
    std::printf("%s: %d random points\n", m.name.c_str(), count);

    // Prepared (NurbsModel::preparePointQueries): cold, a fresh model whose queries make the tree nodes and
    // query cells they are the first to need; then warm, every cell made, as OpenCASCADE's Init prepares its own.
    unidist::NurbsModel prepared({m.surface}, m.solid);
    prepared.preparePointQueries();
    Tally cold, warm;
    for (int pass = 0; pass < 2; ++pass)
      for (std::size_t k = 0; k < qs.size(); ++k) {
        const auto a = Clock::now();
        const unidist::SurfacePoint p = prepared.closestPoint(qs[k]);
        Tally& t = pass == 0 ? cold : warm;
        t.times.push_back(micros(a, Clock::now()));
        t.misses += std::abs(p.signedDistance) > truth[k] + kMiss;
      }
    report(m.name, "unidist prepared cold", cold);
    report(m.name, "unidist prepared", warm);
    const unidist::NurbsModel ours({m.surface}, m.solid);
    for (const Vec& q : qs) (void)ours.closestPoint(q);  // warm the cached tree (OpenCASCADE's Init does its own)
    Tally mine;
    int oracleWorse = 0;
    std::vector<bool> onBoundary;  // the closest point lies on the edge of the parameter domain
    const unidist::NurbsSurface& S = m.surface;
    for (std::size_t k = 0; k < qs.size(); ++k) {
      const auto a = Clock::now();
      const unidist::SurfacePoint p = ours.closestPoint(qs[k]);
      mine.times.push_back(micros(a, Clock::now()));
      const double d = std::abs(p.signedDistance);
      onBoundary.push_back(!m.solid && (p.param[0] <= S.uMin() || p.param[0] >= S.uMax() || p.param[1] <= S.vMin() ||
                                        p.param[1] >= S.vMax()));
      mine.misses += d > truth[k] + kMiss;
      mine.interiorMisses += d > truth[k] + kMiss && !onBoundary[k];
      oracleWorse += d < truth[k] - kMiss;  // the grid oracle polished a local minimum
    }
    report(m.name, "unidist", mine);
    if (oracleWorse) std::printf("  (oracle above ours on %d points: grid + Newton stopped in a local minimum)\n", oracleWorse);

    const Handle(Geom_BSplineSurface) surface = occt_bench::toOcct(m.surface);
    double u0, u1, v0, v1;
    surface->Bounds(u0, u1, v0, v1);
    struct Variant {
      const char* name;
      Extrema_ExtAlgo algo;
      Extrema_ExtFlag flag;
    };
    for (const Variant& v : {Variant{"occt Grad", Extrema_ExtAlgo_Grad, Extrema_ExtFlag_MINMAX},
                             Variant{"occt Tree", Extrema_ExtAlgo_Tree, Extrema_ExtFlag_MINMAX},
                             Variant{"occt Tree MIN", Extrema_ExtAlgo_Tree, Extrema_ExtFlag_MIN}}) {
      GeomAPI_ProjectPointOnSurf projector;
      projector.Init(surface, u0, u1, v0, v1, v.algo);
      projector.SetExtremaFlag(v.flag);
      Tally t;
      for (std::size_t k = 0; k < qs.size(); ++k) {
        const gp_Pnt p(qs[k].x(), qs[k].y(), qs[k].z());
        const auto a = Clock::now();
        projector.Perform(p);
        const bool answered = projector.NbPoints() > 0;
        const double d = answered ? projector.LowerDistance() : 0;
        t.times.push_back(micros(a, Clock::now()));
        t.noAnswer += !answered;
        t.misses += !answered || d > truth[k] + kMiss;
        t.interiorMisses += (!answered || d > truth[k] + kMiss) && !onBoundary[k];
      }
      report(m.name, v.name, t);
    }
  }
}

// ---- surface–surface --------------------------------------------------------------------------------------

void runPairs() {
  std::printf("truth: circle-circle distance off its closed forms by at most %.1e\n", nurbs_truth::closedFormError());
  std::printf("# csv,pair,placement,truth,unidist_us,unidist_value,unidist_status,extss_us,extss_value,"
              "distss_us,distss_value\n");
  int wrongOurs = 0, wrongExtss = 0, wrongDistss = 0, placements = 0;
  const auto wrong = [](double value, double truth) { return !(std::abs(value - truth) <= 1e-6); };
  for (const Placement& p : nurbs_truth::placements()) {
    const unidist::NurbsModel a({p.a}, true), b({p.b}, true);
    unidist::DistanceOptions options;
    options.tolerance = 1e-9;
    unidist::DistanceResult r;
    double ours = 0;
    (void)unidist::distance(a, Eigen::Isometry3d::Identity(), b, p.X_WB, options);  // builds the trees once
    const double tOurs = timeMedian(11, [&] {
      r = unidist::distance(a, Eigen::Isometry3d::Identity(), b, p.X_WB, options);
      return r.distance;
    }, ours);

    const Handle(Geom_BSplineSurface) sa = occt_bench::toOcct(p.a), sb = occt_bench::toOcct(p.b, p.X_WB);
    double extss = 0, distss = 0;
    const double tExt = timeMedian(5, [&] {
      GeomAPI_ExtremaSurfaceSurface e(sa, sb);
      return e.NbExtrema() > 0 ? e.LowerDistance() : std::nan("");
    }, extss);
    const TopoDS_Face fa = occt_bench::faceOf(sa), fb = occt_bench::faceOf(sb);
    const double tDist = timeMedian(3, [&] {
      BRepExtrema_DistShapeShape e(fa, fb);
      return e.IsDone() ? e.Value() : std::nan("");
    }, distss);
    std::printf("%-28s truth %+.12f | unidist %+.12f %-9s %9.1f us | ExtremaSS %+.9f %9.1f us | DistShapeShape "
                "%+.9f %9.1f us\n",
                p.name, p.truth, ours, unidist::toString(r.status), tOurs, extss, tExt, distss, tDist);
    std::printf("csv,pair,%s,%.17g,%.4g,%.17g,%s,%.4g,%.17g,%.4g,%.17g\n", p.name, p.truth, tOurs, ours,
                unidist::toString(r.status), tExt, extss, tDist, distss);
    ++placements;
    wrongOurs += wrong(ours, p.truth);
    wrongExtss += wrong(extss, p.truth);
    wrongDistss += wrong(distss, p.truth);
  }
  std::printf("wrong answers (off the truth by more than 1e-6) of %d placements: unidist %d, ExtremaSS %d, "
              "DistShapeShape %d\n", placements, wrongOurs, wrongExtss, wrongDistss);
}

// ---- our dial ---------------------------------------------------------------------------------------------

void runTolerance() {
  std::printf("# csv,tolerance,placement,relative_tolerance,median_us,error,bound_width,status\n");
  for (const Placement& p : nurbs_truth::placements()) {
    const double size = 2.5;    // the tori's and spheres' bounding-box scale
    for (double rel = 1e-1; rel >= 0.99e-12; rel /= 10) {
      // Fresh models per tolerance: the cached trees would otherwise carry over the tighter runs' refinement.
      const unidist::NurbsModel a({p.a}, true), b({p.b}, true);
      unidist::DistanceOptions options;
      options.tolerance = rel * size;
      unidist::DistanceResult r;
      double value = 0;
      (void)unidist::distance(a, Eigen::Isometry3d::Identity(), b, p.X_WB, options);
      const double t = timeMedian(7, [&] {
        r = unidist::distance(a, Eigen::Isometry3d::Identity(), b, p.X_WB, options);
        return r.distance;
      }, value);
      std::printf("csv,tolerance,%s,%.0e,%.4g,%.3g,%.3g,%s\n", p.name, rel, t, std::abs(value - p.truth),
                  r.upperBound - r.lowerBound, unidist::toString(r.status));
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // line by line: groups run for minutes
  const std::string group = argc > 1 ? argv[1] : "points";
  const int count = argc > 2 ? std::atoi(argv[2]) : 10000;
  if (group == "points") {
    runPoints(count);
  } else if (group == "pairs") {
    runPairs();
  } else if (group == "tolerance") {
    runTolerance();
  } else {
    std::fprintf(stderr, "usage: %s points|pairs|tolerance [queries-per-model]\n", argv[0]);
    return 2;
  }
  return 0;
}
