// The extremes suite's one checking routine: a case is a posed pair, the interval the true signed distance lies
// in (from an oracle that does not go through the library) and an allowance; runCase() checks what every answer
// must satisfy, whatever the pair and however extreme the input (docs/query-contract.md):
//  * nothing NaN (distance, points, normal finite; bounds not NaN — an unknown bound may be ±Inf);
//  * the proved bounds hold the truth: lowerBound <= truth and truth <= upperBound, up to the rounding of the
//    coordinates involved and the NURBS point queries' resolution (a proved bound gets no tolerance slack);
//  * the answer lies inside its own bounds, and pointB − pointA = distance · normal;
//  * a certified distance is within the allowance (tolerance + construction rounding) of the truth;
//  * the query finishes within its CPU-time budget (a hang ends this test's process: the test fails, not the suite).
// Every case is also recorded per (family, extreme) for the table in docs/extremes.md (printed when the
// environment variable UNIDIST_EXTREMES_TABLE is set).
#pragma once

#include "unidist/distance.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>

namespace extremes {

using Vec = Eigen::Vector3d;
using Pose = Eigen::Isometry3d;

/// The true signed distance lies in [lo, hi] (lo == hi for analytic and brute-force truth).
struct Truth {
  double lo = 0, hi = 0;
};

inline Truth exactly(double d) { return {d, d}; }

struct Case {
  std::string family;   ///< "prim-mesh", ... (table row)
  std::string extreme;  ///< "scale 1e-6", "gap 1e-12", ... (table column)
  std::string what;     ///< the models and the configuration, for failure messages
  std::shared_ptr<const unidist::Model> a, b;
  Pose XA = Pose::Identity(), XB = Pose::Identity();
  unidist::DistanceOptions options;
  Truth truth;
  /// CPU-time budget of the query (its thread's CPU time: a shared machine slows wall time, not this). A query
  /// still running after max(20 s, 4 budgets) of wall time is a hang.
  double budgetSeconds = 5;
};

/// Runs the query and checks it (gtest assertions); returns the answer for case-specific checks.
unidist::DistanceResult runCase(const Case& c);

/// The allowance a certified answer of `c` gets: the tolerance in force plus the rounding of the coordinates.
double allowanceOf(const Case& c);

}  // namespace extremes
