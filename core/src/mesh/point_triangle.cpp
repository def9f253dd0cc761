#include "mesh/point_triangle.h"

#include <array>
#include <cmath>
#include <limits>

namespace unidist::mesh {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// Error-free transformations (Knuth's two-sum; the product's error by a fused multiply-add).
inline void twoSum(double a, double b, double& s, double& err) {
  s = a + b;
  const double bb = s - a;
  err = (a - (s - bb)) + (b - bb);
}
inline void twoProduct(double a, double b, double& p, double& err) {
  p = a * b;
  err = std::fma(a, b, -p);
}

// x·y − z·w where x = xh + xl etc. are exact two-term values (a difference of coordinates and its error).
// The leading products are split exactly; the corrections are small and summed plainly, so the result is
// right to a few ulps of itself plus ~ε² of the products' size.
inline double accurateMinor(double xh, double xl, double yh, double yl, double zh, double zl, double wh, double wl) {
  double p1, e1, p2, e2, s, es;
  twoProduct(xh, yh, p1, e1);
  twoProduct(zh, wh, p2, e2);
  twoSum(p1, -p2, s, es);
  const double rest = es + (e1 - e2) + (xh * yl + xl * yh) - (zh * wl + zl * wh) + (xl * yl - zl * wl);
  return s + rest;
}

// Exact sum of a few doubles as a non-overlapping expansion (Shewchuk's grow-expansion); the sum is zero
// exactly when every component is.
template <std::size_t N>
bool exactSumIsZero(const std::array<double, N>& terms) {
  std::array<double, N> e{};
  std::size_t len = 0;
  for (double x : terms) {
    double q = x;
    for (std::size_t i = 0; i < len; ++i) {
      double s, err;
      twoSum(q, e[i], s, err);
      e[i] = err;
      q = s;
    }
    e[len++] = q;
  }
  for (std::size_t i = 0; i < len; ++i)
    if (e[i] != 0.0) return false;
  return true;
}

// x·y − z·w == 0 exactly, with x = xh + xl etc.
bool minorIsZero(double xh, double xl, double yh, double yl, double zh, double zl, double wh, double wl) {
  std::array<double, 16> t{};
  int k = 0;
  const auto add = [&](double a, double b, double sign) {
    double p, err;
    twoProduct(a, b, p, err);
    t[k++] = sign * p;
    t[k++] = sign * err;
  };
  add(xh, yh, 1);
  add(xh, yl, 1);
  add(xl, yh, 1);
  add(xl, yl, 1);
  add(zh, wh, -1);
  add(zh, wl, -1);
  add(zl, wh, -1);
  add(zl, wl, -1);
  return exactSumIsZero(t);
}

struct ExactDiff {
  Eigen::Vector3d hi, lo;
};
inline ExactDiff exactDifference(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {  // a − b
  ExactDiff d;
  for (int i = 0; i < 3; ++i) twoSum(a[i], -b[i], d.hi[i], d.lo[i]);
  return d;
}

// One edge of the boundary: clamped projection onto segment p0 → p1. A clamped end is the vertex itself
// (bit for bit), so vertex answers are exact.
struct EdgeAnswer {
  Eigen::Vector3d point, gap;
  double squaredDistance;
  double t;  // 0 at p0, 1 at p1
};
inline EdgeAnswer onSegment(const Eigen::Vector3d& q, const Eigen::Vector3d& p0, const Eigen::Vector3d& p1) {
  const Eigen::Vector3d e = p1 - p0;
  const Eigen::Vector3d w = q - p0;
  const double ee = e.squaredNorm();
  const double we = w.dot(e);
  EdgeAnswer a;
  if (!(we > 0) || !(ee > 0)) {
    a.point = p0;
    a.t = 0;
    a.gap = w;
  } else if (we >= ee) {
    a.point = p1;
    a.t = 1;
    a.gap = q - p1;
  } else {
    a.t = we / ee;
    a.point = p0 + a.t * e;
    a.gap = w - a.t * e;
  }
  a.squaredDistance = a.gap.squaredNorm();
  return a;
}

}  // namespace

Eigen::Vector3d accurateCross(const Eigen::Vector3d& v0, const Eigen::Vector3d& v1, const Eigen::Vector3d& v2) {
  const ExactDiff d1 = exactDifference(v1, v0), d2 = exactDifference(v2, v0);
  Eigen::Vector3d c;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;  // c_i = d1_j d2_k − d1_k d2_j
    c[i] = accurateMinor(d1.hi[j], d1.lo[j], d2.hi[k], d2.lo[k], d1.hi[k], d1.lo[k], d2.hi[j], d2.lo[j]);
  }
  return c;
}

bool zeroArea(const Eigen::Vector3d& v0, const Eigen::Vector3d& v1, const Eigen::Vector3d& v2) {
  // Fast filter: the plain cross product is within 8ε of its terms' size of the exact one (rounded edge
  // vectors, two products, one difference), so a component beyond that is certainly non-zero.
  {
    const Eigen::Vector3d a = v1 - v0, b = v2 - v0;
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      const double p = a[j] * b[k], q = a[k] * b[j];
      if (std::abs(p - q) > 8.0 * kEps * (std::abs(p) + std::abs(q)) + 64.0 * std::numeric_limits<double>::min())
        return false;
    }
  }
  const ExactDiff d1 = exactDifference(v1, v0), d2 = exactDifference(v2, v0);
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    const double value = accurateMinor(d1.hi[j], d1.lo[j], d2.hi[k], d2.lo[k], d1.hi[k], d1.lo[k], d2.hi[j], d2.lo[j]);
    // When the exact minor is 0 the computed one is at most the rounding of the correction terms,
    // a few ε² of the products (plus underflow); anything larger is certainly non-zero.
    const double size = std::abs(d1.hi[j] * d2.hi[k]) + std::abs(d1.hi[k] * d2.hi[j]);
    const double bound = 64.0 * kEps * kEps * size + 64.0 * std::numeric_limits<double>::denorm_min();
    if (std::abs(value) > bound) return false;
    if (!minorIsZero(d1.hi[j], d1.lo[j], d2.hi[k], d2.lo[k], d1.hi[k], d1.lo[k], d2.hi[j], d2.lo[j])) return false;
  }
  return true;
}

Eigen::Vector3d accurateUnitNormal(const Eigen::Vector3d& v0, const Eigen::Vector3d& v1, const Eigen::Vector3d& v2) {
  const Eigen::Vector3d c = accurateCross(v0, v1, v2);
  const double m = c.cwiseAbs().maxCoeff();
  if (!(m > 0)) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d w = c / m;  // scaled first: |c|² of a tiny triangle underflows
  return w / w.norm();
}

double cornerAngle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d u = a - p, v = b - p;
  return std::atan2(u.cross(v).norm(), u.dot(v));
}

TriangleClosest closestOnTriangle(const Eigen::Vector3d& q, const Eigen::Vector3d& v0, const Eigen::Vector3d& v1,
                                  const Eigen::Vector3d& v2, const Eigen::Vector3d& n) {
  TriangleClosest r;
  const Eigen::Vector3d w0 = q - v0;
  if (n.x() != 0.0 || n.y() != 0.0 || n.z() != 0.0) {
    // Sides of q's projection with respect to the three edge lines (twice the signed sub-areas).
    const double s01 = n.dot((v1 - v0).cross(w0));
    const double s12 = n.dot((v2 - v1).cross(q - v1));
    const double s20 = n.dot((v0 - v2).cross(q - v2));
    if (s01 > 0 && s12 > 0 && s20 > 0) {
      const double h = n.dot(w0);
      r.gap = h * n;
      r.point = q - r.gap;
      r.squaredDistance = h * h;
      r.feature = TriangleFeature::Face;
      const double total = s01 + s12 + s20;
      r.b1 = s20 / total;
      r.b2 = s01 / total;
      return r;
    }
  }
  // On the boundary: the best of the three edges (the first on exact ties).
  const EdgeAnswer a01 = onSegment(q, v0, v1), a12 = onSegment(q, v1, v2), a20 = onSegment(q, v2, v0);
  int best = 0;
  if (a12.squaredDistance < a01.squaredDistance) best = 1;
  if (a20.squaredDistance < (best == 0 ? a01.squaredDistance : a12.squaredDistance)) best = 2;
  const EdgeAnswer& a = best == 0 ? a01 : (best == 1 ? a12 : a20);
  r.point = a.point;
  r.gap = a.gap;
  r.squaredDistance = a.squaredDistance;
  using F = TriangleFeature;
  static constexpr F kEdge[3] = {F::Edge01, F::Edge12, F::Edge20};
  static constexpr F kStart[3] = {F::Vertex0, F::Vertex1, F::Vertex2};
  static constexpr F kEnd[3] = {F::Vertex1, F::Vertex2, F::Vertex0};
  r.feature = a.t == 0 ? kStart[best] : (a.t == 1 ? kEnd[best] : kEdge[best]);
  switch (best) {
    case 0: r.b1 = a.t, r.b2 = 0; break;
    case 1: r.b1 = 1 - a.t, r.b2 = a.t; break;
    default: r.b1 = 0, r.b2 = 1 - a.t; break;
  }
  return r;
}

TriangleClosest closestOnTriangle(const Eigen::Vector3d& q, const Eigen::Vector3d& v0, const Eigen::Vector3d& v1,
                                  const Eigen::Vector3d& v2) {
  return closestOnTriangle(q, v0, v1, v2, accurateUnitNormal(v0, v1, v2));
}

}  // namespace unidist::mesh
