// Model–model distance, signed: the one query every representation pair answers. The exact meaning of
// every field is docs/query-contract.md (kept in step with ../shared/docs/query-contract.md).
#pragma once

#include "unidist/model.h"
#include "unidist/query_options.h"

namespace unidist {

/// What distance() computes; the cheaper kinds stop earlier.
enum class Compute {
  /// Whether the models overlap: stops as soon as the bounds exclude 0 (lowerBound > 0: apart; upperBound <= 0:
  /// touching or overlapping), trying a coarse tolerance first; within the tolerance of touching it is decided
  /// by `distance <= 0`. Neither a separation nor an overlap is measured to the tolerance (lowerBound may be
  /// −inf); status Certified says the verdict is proved.
  Overlap,
  /// The distance of separated models, at the requested tolerance; an overlap is proved but not measured
  /// (upperBound <= 0, lowerBound may be −inf): no penetration-depth solve.
  Separation,
  /// The signed distance, penetration depth included (the default).
  SignedDistance,
};

const char* toString(Compute c);

struct DistanceOptions : QueryOptions {
  Compute compute = Compute::SignedDistance;
  /// Grow A / B by a ball of this radius (a swept sphere); >= 0.
  double inflateA = 0, inflateB = 0;
};

struct DistanceResult {
  double distance = 0;                                  ///< signed: < 0 is −(minimum translation distance)
  Eigen::Vector3d pointA = Eigen::Vector3d::Zero();     ///< world, on A's surface (its stand-in's at a level of detail)
  Eigen::Vector3d pointB = Eigen::Vector3d::Zero();     ///< world, on B's surface; pointB − pointA = distance · normal
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();    ///< unit; A toward B, or the way B moves to separate
  double lowerBound = -std::numeric_limits<double>::infinity();  ///< proved: lowerBound <= true distance
  double upperBound = std::numeric_limits<double>::infinity();   ///< proved: true distance <= upperBound
  int iterations = 0;
  Status status = Status::Bounded;
  const char* method = "";                              ///< which algorithm answered (for diagnostics and docs)

  /// The achieved accuracy: the true distance is within this of `distance` (the width of the proved bounds).
  double errorBound() const { return upperBound - lowerBound; }
  /// The overlap verdict: touching or overlapping (proved when upperBound <= 0; within the tolerance otherwise).
  bool overlapping() const { return distance <= 0; }
};

/// Tolerance used when options.tolerance < 0: 1e-9 × the larger bounding-box diagonal of the posed models
/// (an unbounded model contributes nothing; two unbounded models give 1e-9).
double defaultTolerance(const Model& a, const Eigen::Isometry3d& X_WA, const Model& b, const Eigen::Isometry3d& X_WB);

/// Signed distance between A at pose X_WA and B at pose X_WB. Throws InputError for a pair that has no
/// defined answer (two half-spaces) or a non-finite pose.
DistanceResult distance(const Model& a, const Eigen::Isometry3d& X_WA, const Model& b, const Eigen::Isometry3d& X_WB,
                        const DistanceOptions& options = {});

/// The generic path alone (alternating point-to-model queries with several starts, then a branch-and-bound
/// pass over surface cells that bounds the answer): works for any two models; exposed for tests and benchmarks.
DistanceResult genericDistance(const Model& a, const Eigen::Isometry3d& X_WA, const Model& b,
                               const Eigen::Isometry3d& X_WB, const DistanceOptions& options = {});

}  // namespace unidist
