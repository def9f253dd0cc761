// Private helpers shared by the primitives: input validation, number formatting and unit vectors that
// stay unit for any finite input (tiny, subnormal or huge), so no answer ever turns into NaN.
#pragma once

#include "unidist/types.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace unidist::prim {

/// Shortest "%.*g" text that reads back to the same double ("-1", "0.1", "nan", "inf").
std::string formatNumber(double x);

/// Throws InputError "<shape>: <field> must be finite and > 0 (got <value>)" unless value is.
void requirePositive(const char* shape, const char* field, double value);

/// Throws InputError "<what> <index> has a non-finite coordinate (x, y, z)" or "... has a coordinate beyond
/// +-1e30 (x, y, z); scale the model" (kMaxModelCoordinate: the mesh and cloud hierarchies keep float boxes).
void requireModelCoordinate(const Eigen::Vector3d& p, const char* what, std::size_t index);

/// A number with %.17g, as describe() prints sizes.
std::string exact(double x);

/// v / |v|, or fallback when v = 0. Scales by the largest component first: |v|² of a tiny vector
/// underflows and of a huge one overflows, and either would give a vector that is not unit.
inline Eigen::Vector3d unitOr(const Eigen::Vector3d& v, const Eigen::Vector3d& fallback) {
  const double m = v.cwiseAbs().maxCoeff();
  if (!(m > 0)) return fallback;
  const Eigen::Vector3d w = v / m;
  return w / w.norm();
}

/// |v| without underflow or overflow.
inline double robustNorm(const Eigen::Vector3d& v) {
  const double m = v.cwiseAbs().maxCoeff();
  return m > 0 ? m * (v / m).norm() : 0.0;
}

/// Unit 2-vector along (x, y), or (fx, fy) when both are 0; same scaling argument as unitOr.
inline Eigen::Vector2d unit2Or(double x, double y, double fx, double fy) {
  const double m = std::max(std::abs(x), std::abs(y));
  if (!(m > 0)) return {fx, fy};
  const double a = x / m, b = y / m;
  const double n = std::hypot(a, b);
  return {a / n, b / n};
}

/// Radial direction of (x, y) about the z axis; +x on the axis (the documented tie rule).
inline Eigen::Vector2d radialDirection(double x, double y) { return unit2Or(x, y, 1.0, 0.0); }

}  // namespace unidist::prim
