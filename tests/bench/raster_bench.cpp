// Kim, Hoff, Lin & Manocha's image-space queries, rendered headless through OSMesa (core/raster, docs/raster.md):
//   query  — closest boundary point among ~45 random convex polytopes × ~40 faces and ~70 × ~30 overlapping
//            around O (the paper: 0.1 s and 0.07 s on a GeForce 3);
//   tori   — penetration depth of two interlocked tori of ~1,000 triangles each, 32 convex ring segments each
//            (the paper: 2,000 faces, 67 pieces, 0.2 s of which 0.04 s the query);
//   sweep  — resolution 32² … 1024² per cube face: PD error against an exact oracle (box–box: the separating
//            axes; tori: the ray version of the algorithm, finely sampled and polished) and median time.
// Prints a table and "csv," lines (their headers as "# csv,"); tests/bench/run_raster_benchmarks.sh keeps them.
// usage: unidist_bench_raster [query|tori|sweep|all] [runs]
#include "median.h"
#include "raster/raster_fixtures.h"
#include "unidist/primitives.h"
#include "unidist/raster/convex_union.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <string>

using namespace raster_test;
using unidist::raster::BoundaryPoint;
using unidist::raster::BoundaryQueryOptions;
using unidist::raster::OffscreenContext;
using unidist::raster::UnionDistanceOptions;
using unidist::raster::UnionDistanceReport;

namespace {

/// Median seconds of `runs` calls.
double timeRuns(int runs, const std::function<void()>& call) {
  std::vector<double> seconds;
  for (int k = 0; k < runs; ++k) {
    const auto start = std::chrono::steady_clock::now();
    call();
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return median(seconds);
}

/// `count` random convex polytopes of about `faces` triangles (hulls of faces/2 + 2 points on random ellipsoids)
/// scattered in a ball of radius 0.6 around the origin; the first is centred on it, so O is inside.
ConvexUnion randomPolytopes(int count, int faces, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1, 1), axis(0.3, 0.7);
  std::normal_distribution<double> gauss;
  ConvexUnion pieces;
  for (int k = 0; k < count; ++k) {
    Vec centre = Vec::Zero();
    if (k > 0) do centre = Vec(unit(rng), unit(rng), unit(rng)); while (centre.norm() > 1);
    const Eigen::Isometry3d X = Eigen::Translation3d(0.6 * centre) *
                                Eigen::Quaterniond(gauss(rng), gauss(rng), gauss(rng), gauss(rng)).normalized();
    const Vec semi(axis(rng), axis(rng), axis(rng));
    std::vector<Vec> points;
    for (int p = 0; p < faces / 2 + 2; ++p) {
      const Vec g = Vec(gauss(rng), gauss(rng), gauss(rng)).normalized();
      points.push_back(X * Vec(semi.cwiseProduct(g)));
    }
    pieces.push_back(unidist::raster::convexHull(points));
  }
  return pieces;
}

int triangles(const ConvexUnion& u) {
  int n = 0;
  for (const auto& p : u) n += static_cast<int>(p.triangles.size());
  return n;
}

void query(OffscreenContext& context, int runs) {
  std::printf("\n== closest boundary point among random convex polytopes around O ==\n");
  std::printf("# csv,query,pieces,triangles,resolution,median_s,passes,rendered,culled,pixel_distance,distance,"
              "lower_bound,paper_s\n");
  struct Case {
    int count, faces;
    double paper;
  };
  for (const Case c : {Case{45, 40, 0.1}, Case{70, 30, 0.07}}) {
    const ConvexUnion pieces = randomPolytopes(c.count, c.faces, 7u + static_cast<unsigned>(c.count));
    for (int n : {64, 128, 256, 512}) {
      BoundaryQueryOptions options;
      options.resolution = n;
      BoundaryPoint bp;
      const double s = timeRuns(runs, [&] { bp = closestBoundaryPoint(context, pieces, Vec::Zero(), options); });
      std::printf("%2d polytopes, %4d triangles, %4d²: %8.4f s  passes %3d  rendered %4d  culled %4d  d = %.9f "
                  "(pixels %.9f, lower %.6f)  paper %.2f s\n",
                  c.count, triangles(pieces), n, s, bp.passes, bp.piecesRendered, bp.piecesCulled, bp.distance,
                  bp.pixelDistance, bp.lowerBound, c.paper);
      std::printf("csv,query,%d,%d,%d,%.6f,%d,%d,%d,%.12g,%.12g,%.12g,%.2f\n", c.count, triangles(pieces), n, s,
                  bp.passes, bp.piecesRendered, bp.piecesCulled, bp.pixelDistance, bp.distance, bp.lowerBound,
                  c.paper);
    }
  }
}

UnionDistanceReport unidistReport(OffscreenContext& context, const ConvexUnion& a, const ConvexUnion& b,
                                  const Eigen::Isometry3d& X_WB, const UnionDistanceOptions& o) {
  return unionDistanceReport(context, a, Eigen::Isometry3d::Identity(), b, X_WB, o);
}

/// Two interlocked tori (B turned upright and pushed into A's tube), each 32 convex ring segments × 16 sides.
struct Tori {
  ConvexUnion a = torusPieces(1.0, 0.3, 32, 16, Eigen::Isometry3d::Identity());
  ConvexUnion b = torusPieces(1.0, 0.3, 32, 16, Eigen::Isometry3d::Identity());
  Eigen::Isometry3d X_WB = Eigen::Translation3d(1.45, 0.03, 0.02) * Eigen::AngleAxisd(M_PI / 2, Vec::UnitX());
};

void tori(OffscreenContext& context, int runs) {
  std::printf("\n== penetration depth of interlocked tori (32 convex segments each) ==\n");
  std::printf("# csv,tori,pieces,triangles,resolution,median_s,sums_s,query_s,sums,overlapping_pairs,distance,"
              "lower_bound,upper_bound,paper_s,paper_query_s\n");
  const Tori t;
  for (int n : {64, 128, 256, 512}) {
    UnionDistanceOptions options;
    options.resolution = n;
    std::vector<double> sums, queries;
    UnionDistanceReport report;
    const double s = timeRuns(runs, [&] {
      report = unionDistanceReport(context, t.a, Eigen::Isometry3d::Identity(), t.b, t.X_WB, options);
      sums.push_back(report.sumsSeconds);
      queries.push_back(report.querySeconds);
    });
    const auto& r = report.result;
    std::printf("%d pieces, %d triangles, %4d²: %.4f s (sums %.4f s, query %.4f s), %d sums (%d overlapping), "
                "PD %.9f in [%.9f, %.9f]  paper 0.2 s (query 0.04 s)\n",
                static_cast<int>(t.a.size() + t.b.size()), triangles(t.a) + triangles(t.b), n, s, median(sums),
                median(queries), report.sums, report.overlappingPairs, -r.distance, -r.upperBound, -r.lowerBound);
    std::printf("csv,tori,%d,%d,%d,%.6f,%.6f,%.6f,%d,%d,%.12g,%.12g,%.12g,0.2,0.04\n",
                static_cast<int>(t.a.size() + t.b.size()), triangles(t.a) + triangles(t.b), n, s, median(sums),
                median(queries), report.sums, report.overlappingPairs, r.distance, r.lowerBound, r.upperBound);
  }
}

/// The union of the Minkowski sums A_i ⊕ (−B_j) within `reach` of the origin (the others cannot matter).
ConvexUnion sumsWithin(const ConvexUnion& a, const ConvexUnion& b, const Eigen::Isometry3d& X_WB, double reach) {
  ConvexUnion sums;
  for (const auto& pa : a)
    for (const auto& pb : b) {
      std::vector<Vec> d;
      for (const auto& p : pa.vertices)
        for (const auto& q : pb.vertices) d.push_back(p - X_WB * q);
      unidist::Aabb box;
      for (const auto& v : d) box.extend(v);
      if (box.distanceTo(Vec::Zero()) <= reach) sums.push_back(unidist::raster::convexHull(d));
    }
  return sums;
}

void sweep(OffscreenContext& context, int runs) {
  std::printf("\n== resolution sweep: PD error against an exact oracle, and time ==\n");
  std::printf("# csv,sweep,case,resolution,median_s,pixel_error,polished_error,answer_error,face_bound,crease_bound,truth\n");
  struct Case {
    std::string name;
    ConvexUnion a, b;
    Eigen::Isometry3d X_WA, X_WB;
    double truth;
  };
  std::vector<Case> cases;
  {  // box–box: one Minkowski sum; the separating axes give the exact depth (core's box–box routine)
    const Vec ha(1.0, 0.5, 0.3), hb(0.4, 0.4, 0.4);
    const Eigen::Isometry3d X_WA(Eigen::AngleAxisd(0.2, Vec::UnitZ()));
    const Eigen::Isometry3d X_WB = Eigen::Translation3d(1.1, 0.2, 0.1) * Eigen::AngleAxisd(0.7, Vec(1, 2, 3).normalized());
    cases.push_back({"box-box", {box(-ha, ha)}, {box(-hb, hb)}, X_WA, X_WB,
                     -unidist::distance(unidist::Box(ha), X_WA, unidist::Box(hb), X_WB).distance});
  }
  {  // a cube in the notch of an L, 0.1 into one arm and 0.15 into the other: it must clear both, a crease of
     // the sums (first order in the resolution); truth by construction
    const Vec h(0.25, 0.25, 0.25);
    cases.push_back({"L-notch", {box(Vec(0, 0, 0), Vec(3, 1, 1)), box(Vec(0, 0, 0), Vec(1, 3, 1))}, {box(-h, h)},
                     Eigen::Isometry3d::Identity(), Eigen::Isometry3d(Eigen::Translation3d(1.15, 1.1, 0.5)),
                     std::hypot(0.1, 0.15)});
  }
  // Tori, as in `tori`, and pushed deeper (there the union, not one pair, decides): the ray version over the
  // sums within the proved depth bound, 96² per face, then a 64-direction compass search.
  const Tori t;
  for (const double push : {1.45, 1.5}) {
    const Eigen::Isometry3d X_WB = Eigen::Translation3d(push, push == 1.45 ? 0.03 : 0.05, 0.02) *
                                   Eigen::AngleAxisd(M_PI / 2, Vec::UnitX());
    UnionDistanceOptions o;
    o.resolution = 32;
    const double reach = -unidistReport(context, t.a, t.b, X_WB, o).result.lowerBound + 1e-9;
    const ConvexUnion sums = sumsWithin(t.a, t.b, X_WB, reach);
    cases.push_back({push == 1.45 ? "tori" : "tori-deep", t.a, t.b, Eigen::Isometry3d::Identity(), X_WB,
                     oracleDistance(sums, Vec::Zero(), 96, 1e-13, nullptr, 400000, 64)});
  }
  for (const Case& c : cases) std::printf("oracle %-9s depth %.15f\n", c.name.c_str(), c.truth);
  std::printf("(face bound: inside a facet, second order; crease bound: a right-angled groove, first order)\n");

  for (int n = 32; n <= 1024; n *= 2)
    for (const Case& c : cases) {
      UnionDistanceOptions options;
      options.resolution = n;
      options.refine = false;
      UnionDistanceReport raw;
      const double s = timeRuns(runs, [&] { raw = unionDistanceReport(context, c.a, c.X_WA, c.b, c.X_WB, options); });
      options.refine = true;
      const UnionDistanceReport polished = unionDistanceReport(context, c.a, c.X_WA, c.b, c.X_WB, options);
      // The image alone, the image polished on the CPU, and the final answer (which may be a pair's free escape).
      const double pixelError = raw.boundary.pixelDistance - c.truth;
      const double polishedError = polished.boundary.distance - c.truth;
      const double answerError = -polished.result.distance - c.truth;
      const double faceBound = unidist::raster::resolutionErrorBound(c.truth, n, M_PI / 2);
      std::printf("%-9s %4d²: %.4f s  pixel error %.3e  polished %+.3e  answer %+.3e  (face bound %.3e)  %s\n",
                  c.name.c_str(), n, s, pixelError, polishedError, answerError, faceBound,
                  unidist::toString(polished.result.status));
      const double creaseBound = unidist::raster::resolutionErrorBound(c.truth, n, M_PI / 4);
      std::printf("csv,sweep,%s,%d,%.6f,%.6e,%.6e,%.6e,%.6e,%.6e,%.15g\n", c.name.c_str(), n, s, pixelError,
                  polishedError, answerError, faceBound, creaseBound, c.truth);
    }
}

}  // namespace

int main(int argc, char** argv) {
  const std::string group = argc > 1 ? argv[1] : "all";
  const int runs = argc > 2 ? std::max(1, std::atoi(argv[2])) : 5;
  OffscreenContext context(64, 64);
  if (group == "query" || group == "all") query(context, runs);
  if (group == "tori" || group == "all") tori(context, runs);
  if (group == "sweep" || group == "all") sweep(context, runs);
  return 0;
}
