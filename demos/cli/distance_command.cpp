// `unidist distance A B [--pose-a P] [--pose-b P] [--tol T] [--rel-tol R] [--max-iterations N] [--detail-a D]
// [--detail-b D] [--compute overlap|separation|signed-distance] [--inflate-a R] [--inflate-b R]
// [--pd exact|raster] [--resolution N] [--json]`: the query of docs/query-contract.md, printed as one JSON object
// or as a short report. --pd raster reads A and B as unions of convex pieces and answers with unidist::raster
// (docs/raster.md); of the dial it takes --tol and --max-iterations.
#include "commands.h"
#include "output.h"

#include "unidist/adapters/convex_pieces.h"
#include "unidist/adapters/load.h"
#include "unidist/adapters/spec.h"
#include "unidist/distance.h"
#ifdef UNIDIST_HAVE_RASTER
#include "unidist/raster/convex_piece.h"
#endif

#include <chrono>
#include <climits>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace unidist::cli {
namespace {

/// A non-negative finite number given to `option`.
double nonNegative(const std::string& text, const char* option) {
  const double v = parseNumber(text, option);
  if (v < 0) throw InputError(std::string(option) + " must be >= 0 (got " + textNumber(v) + ")");
  return v;
}

Compute parseCompute(const std::string& text) {
  for (Compute c : {Compute::Overlap, Compute::Separation, Compute::SignedDistance})
    if (text == toString(c)) return c;
  throw InputError("--compute must be 'overlap', 'separation' or 'signed-distance' (got '" + text + "')");
}

Eigen::Isometry3d poseOrIdentity(bool given, const std::string& text, const char* option) {
  return given ? parsePose(text, option) : Eigen::Isometry3d::Identity();
}

std::shared_ptr<const Model> load(const std::string& specOrPath, const char* which) {
  try {
    return loadModel(specOrPath);
  } catch (const InputError& e) {
    throw InputError(std::string(which) + ": " + e.what());
  }
}

/// What one query answered, with its wall time and the bounding-box diagonals the default tolerance uses.
struct Answer {
  DistanceResult result;
  double timeUs = 0;
  double buildUs = 0;  // what was built before the query (a level of detail's stand-ins)
  double tolerance = 0;
};

Answer exactAnswer(const DistanceArgs& args, const DistanceOptions& options, const Eigen::Isometry3d& X_WA,
                   const Eigen::Isometry3d& X_WB) {
  const std::shared_ptr<const Model> a = load(args.a, "A");
  const std::shared_ptr<const Model> b = load(args.b, "B");
  Answer answer;
  // The stand-ins of a level of detail are built once per model and level, like any acceleration structure:
  // their cost is build time, not query time.
  if (options.detailA > 0 || options.detailB > 0) {
    const auto build = std::chrono::steady_clock::now();
    (void)a->atDetail(options.detailA);
    (void)b->atDetail(options.detailB);
    answer.buildUs = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - build).count();
  }
  const auto start = std::chrono::steady_clock::now();
  answer.result = distance(*a, X_WA, *b, X_WB, options);
  answer.timeUs = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
  answer.tolerance = options.tolerance >= 0 ? options.tolerance : defaultTolerance(*a, X_WA, *b, X_WB);
  return answer;
}

#ifdef UNIDIST_HAVE_RASTER
raster::ConvexUnion loadUnion(const std::string& specOrPath, const char* which) {
  try {
    raster::ConvexUnion pieces;
    for (const PieceSource& p : loadConvexPieces(specOrPath))
      pieces.push_back(raster::convexPiece(p.vertices, p.triangles, p.name));
    return pieces;
  } catch (const InputError& e) {
    throw InputError(std::string(which) + ": " + e.what());
  }
}

double posedDiagonal(const raster::ConvexUnion& pieces, const Eigen::Isometry3d& X) {
  Aabb box;
  for (const raster::ConvexPolytope& p : pieces)
    for (const Eigen::Vector3d& v : p.vertices) box.extend(X * v);
  return box.diagonal();
}

Answer rasterAnswer(const DistanceArgs& args, const DistanceOptions& options, const Eigen::Isometry3d& X_WA,
                    const Eigen::Isometry3d& X_WB) {
  if (args.hasInflateA || args.hasInflateB) throw InputError("--pd raster does not take --inflate-a/--inflate-b");
  raster::UnionDistanceOptions unionOptions;
  unionOptions.tolerance = options.tolerance;
  if (args.dial.hasMaxIterations) unionOptions.maxIterations = options.maxIterations;  // its GJK cap per pair
  if (args.hasResolution) {
    const double n = parseNumber(args.resolution, "--resolution");
    if (n != std::floor(n) || n < 8 || n > 4096)
      throw InputError("--resolution must be a whole number of pixels in 8..4096 (got " + args.resolution + ")");
    unionOptions.resolution = static_cast<int>(n);
  }
  const raster::ConvexUnion a = loadUnion(args.a, "A");
  const raster::ConvexUnion b = loadUnion(args.b, "B");
  Answer answer;
  answer.tolerance = options.tolerance >= 0 ? options.tolerance
                                            : 1e-9 * std::max(posedDiagonal(a, X_WA), posedDiagonal(b, X_WB));
  const auto start = std::chrono::steady_clock::now();
  raster::OffscreenContext context(unionOptions.resolution, unionOptions.resolution);
  answer.result = raster::unionDistance(context, a, X_WA, b, X_WB, unionOptions);
  answer.timeUs = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
  return answer;
}
#endif

}  // namespace

void applyDial(const DialArgs& args, QueryOptions& options) {
  if (args.hasTol) options.tolerance = nonNegative(args.tol, "--tol");  // absent: -1 → the contract's default
  if (args.hasRelTol) options.relativeTolerance = nonNegative(args.relTol, "--rel-tol");
  if (args.hasMaxIterations) {
    const double n = parseNumber(args.maxIterations, "--max-iterations");
    if (n < 1 || n != std::floor(n) || n > INT_MAX)
      throw InputError("--max-iterations must be a whole number >= 1 (got " + args.maxIterations + ")");
    options.maxIterations = static_cast<int>(n);
  }
  if (args.hasDetailA) options.detailA = nonNegative(args.detailA, "--detail-a");
  if (args.hasDetailB) options.detailB = nonNegative(args.detailB, "--detail-b");
}

std::string runDistance(const DistanceArgs& args) {
  const bool raster = args.hasPd && args.pd == "raster";
  if (args.hasPd && !raster && args.pd != "exact")
    throw InputError("--pd must be 'exact' or 'raster' (got '" + args.pd + "')");
  if (args.hasResolution && !raster) throw InputError("--resolution needs --pd raster");
  DistanceOptions options;
  applyDial(args.dial, options);
  if (args.hasCompute) options.compute = parseCompute(args.compute);
  if (args.hasInflateA) options.inflateA = nonNegative(args.inflateA, "--inflate-a");
  if (args.hasInflateB) options.inflateB = nonNegative(args.inflateB, "--inflate-b");
  if (raster) {  // what the raster path does not do is refused, not ignored; the defaults' values are accepted
    if (options.compute != Compute::SignedDistance)
      throw InputError(std::string("--compute ") + toString(options.compute) +
                       " needs --pd exact (--pd raster computes the signed distance)");
    if (options.detailA > 0 || options.detailB > 0)
      throw InputError("--pd raster does not take --detail-a/--detail-b (its convex pieces are used exactly)");
    if (options.relativeTolerance > 0) throw InputError("--pd raster does not take --rel-tol");
  }
  const Eigen::Isometry3d X_WA = poseOrIdentity(args.hasPoseA, args.poseA, "--pose-a");
  const Eigen::Isometry3d X_WB = poseOrIdentity(args.hasPoseB, args.poseB, "--pose-b");
#ifdef UNIDIST_HAVE_RASTER
  const Answer answer = raster ? rasterAnswer(args, options, X_WA, X_WB) : exactAnswer(args, options, X_WA, X_WB);
#else
  if (raster)
    throw InputError("--pd raster: this unidist was built without the raster target (install libosmesa6-dev and "
                     "libqhull-dev, then rebuild)");
  const Answer answer = exactAnswer(args, options, X_WA, X_WB);
#endif
  const DistanceResult& r = answer.result;
  const double timeUs = answer.timeUs;
  // Acceleration structures are built inside the timed query, on first need; a level of detail's stand-ins before.
  const double buildUs = answer.buildUs;

  if (!std::isfinite(r.distance) || !r.pointA.allFinite() || !r.pointB.allFinite() || !r.normal.allFinite())
    throw std::runtime_error(std::string("the query returned a non-finite answer (method ") + r.method + ")");

  std::string out;
  if (args.json) {
    out = "{\"distance\": " + jsonNumber(r.distance) + ", \"point_a\": " + jsonVector(r.pointA) +
          ", \"point_b\": " + jsonVector(r.pointB) + ", \"normal\": " + jsonVector(r.normal) +
          ", \"lower_bound\": " + jsonNumber(r.lowerBound) + ", \"upper_bound\": " + jsonNumber(r.upperBound) +
          ", \"status\": " + jsonString(toString(r.status)) + ", \"iterations\": " + std::to_string(r.iterations) +
          ", \"time_us\": " + jsonNumber(timeUs) + ", \"build_us\": " + jsonNumber(buildUs) + "}\n";
  } else {
    out += "distance     " + textNumber(r.distance) + "\n";
    out += "bounds       [" + textNumber(r.lowerBound) + ", " + textNumber(r.upperBound) + "]\n";
    out += "status       " + std::string(toString(r.status)) + " (tolerance " +
           textNumber(answer.tolerance) + ")\n";
    out += "point_a      " + textVector(r.pointA) + "\n";
    out += "point_b      " + textVector(r.pointB) + "\n";
    out += "normal       " + textVector(r.normal) + "\n";
    out += "method       " + std::string(*r.method ? r.method : "-") + ", " + std::to_string(r.iterations) +
           " iterations\n";
    char time[64];  // a wall time: 0.1 us resolution is all it has
    std::snprintf(time, sizeof time, "%.1f us (build %.1f us)", timeUs, buildUs);
    out += "time         " + std::string(time) + "\n";
  }
  return out;
}

}  // namespace unidist::cli
