// `unidist distance A B [--pose-a P] [--pose-b P] [--tol T] [--inflate-a R] [--inflate-b R] [--json]`:
// the query of docs/query-contract.md, printed as one JSON object or as a short report.
#include "commands.h"
#include "output.h"

#include "unidist/adapters/load.h"
#include "unidist/adapters/spec.h"
#include "unidist/distance.h"

#include <chrono>
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

}  // namespace

std::string runDistance(const DistanceArgs& args) {
  DistanceOptions options;
  if (args.hasTol) options.tolerance = nonNegative(args.tol, "--tol");  // absent: -1 → the contract's default
  if (args.hasInflateA) options.inflateA = nonNegative(args.inflateA, "--inflate-a");
  if (args.hasInflateB) options.inflateB = nonNegative(args.inflateB, "--inflate-b");
  const Eigen::Isometry3d X_WA = poseOrIdentity(args.hasPoseA, args.poseA, "--pose-a");
  const Eigen::Isometry3d X_WB = poseOrIdentity(args.hasPoseB, args.poseB, "--pose-b");
  const std::shared_ptr<const Model> a = load(args.a, "A");
  const std::shared_ptr<const Model> b = load(args.b, "B");

  const auto start = std::chrono::steady_clock::now();
  const DistanceResult r = distance(*a, X_WA, *b, X_WB, options);
  const auto stop = std::chrono::steady_clock::now();
  const double timeUs = std::chrono::duration<double, std::micro>(stop - start).count();
  const double buildUs = 0;  // primitives build no acceleration structure

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
           textNumber(options.tolerance >= 0 ? options.tolerance : defaultTolerance(*a, X_WA, *b, X_WB)) + ")\n";
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
