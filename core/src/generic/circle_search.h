// Certified global minimum of a function of an angle, by best-first branch and bound over intervals.
// Used by every pair that involves a torus: a torus is its centre circle swept by a ball, so its distance
// to anything is a minimum over the circle's angle.
#pragma once

#include <functional>

namespace unidist::detail {

struct AngleSample {
  double value;      ///< g(θ)
  double slope;      ///< g'(θ) (only used with a curvature bound)
  double curvature;  ///< g'' >= −curvature on the interval the sample stands for; < 0 when unknown
};

/// g(θ) for the interval [θ − halfWidth, θ + halfWidth] (the width lets g bound its curvature there).
using AngleFunction = std::function<AngleSample(double theta, double halfWidth)>;

struct AngleMinimum {
  double theta = 0;     ///< where the best value was found
  double value = 0;     ///< best g found (an upper bound on the minimum)
  double lowerBound = 0;  ///< proved: min g >= lowerBound
  int evaluations = 0;
  bool certified = false;  ///< value - lowerBound <= tolerance
};

/// Minimises g over [0, 2π). Bounds on an interval of half-width h around its middle m use
///  * first order:  g >= g(m) − lipschitz·h                               (always)
///  * second order: g >= g(m) − |g'(m)|·h − curvature·h²/2  where the sample gives a curvature bound.
/// Stops when the bounds meet within tolerance or after maxEvaluations samples; honest either way.
AngleMinimum minimizeOverAngle(const AngleFunction& g, double lipschitz, double tolerance, int maxEvaluations);

/// Proves min g >= threshold (true), finds a sample below it (false), or runs out of budget (false).
bool provesAbove(const AngleFunction& g, double lipschitz, double threshold, int maxEvaluations);

}  // namespace unidist::detail
