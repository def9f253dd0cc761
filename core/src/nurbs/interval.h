// Interval arithmetic for enclosures of polynomial and rational quantities over a parameter box (round to
// nearest: callers widen what they conclude from it, as everywhere in the NURBS code). Internal.
#pragma once

#include <algorithm>
#include <array>

namespace unidist::nurbs {

struct Interval {
  double lo = 0, hi = 0;
  /// The largest |x| over the interval.
  double magnitude() const { return std::max(-lo, hi); }
};

inline Interval operator+(Interval a, Interval b) { return {a.lo + b.lo, a.hi + b.hi}; }
inline Interval operator-(Interval a, Interval b) { return {a.lo - b.hi, a.hi - b.lo}; }
inline Interval operator-(Interval a) { return {-a.hi, -a.lo}; }
inline Interval operator*(double c, Interval a) { return c >= 0 ? Interval{c * a.lo, c * a.hi} : Interval{c * a.hi, c * a.lo}; }
inline Interval operator*(Interval a, Interval b) {
  const double p0 = a.lo * b.lo, p1 = a.lo * b.hi, p2 = a.hi * b.lo, p3 = a.hi * b.hi;
  return {std::min({p0, p1, p2, p3}), std::max({p0, p1, p2, p3})};
}
/// a / w for w > 0 throughout.
inline Interval dividedByPositive(Interval a, Interval w) { return a * Interval{1 / w.hi, 1 / w.lo}; }

/// A box of 3-vectors.
using IntervalVec3 = std::array<Interval, 3>;

inline IntervalVec3 operator+(const IntervalVec3& a, const IntervalVec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline IntervalVec3 operator-(const IntervalVec3& a, const IntervalVec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline IntervalVec3 operator-(const IntervalVec3& a) { return {-a[0], -a[1], -a[2]}; }
inline IntervalVec3 operator*(Interval c, const IntervalVec3& a) { return {c * a[0], c * a[1], c * a[2]}; }
inline Interval dot(const IntervalVec3& a, const IntervalVec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

}  // namespace unidist::nurbs
