// GJK distance with the signed-volume sub-distance (Montanari, Petrinic & Barbieri, ACM TOG 2017), and the
// driver that hands overlapping pairs to EPA (epa.cpp). See gjk.h for the bounds and what they prove.
#include "convex/gjk.h"
#include "convex/gjk_loop.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace unidist::detail {
namespace {

using Eigen::Vector3d;

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Strict agreement of signs; a zero agrees with nothing, so a degenerate (zero-volume or zero-area) simplex
// always falls through to the test of its faces.
bool sameSign(double a, double b) { return (a > 0 && b > 0) || (a < 0 && b < 0); }

SubSimplex single(const Vector3d* p, int i) {
  SubSimplex s;
  s.count = 1;
  s.index[0] = i;
  s.lambda[0] = 1;
  s.v = p[i];
  return s;
}

// Keeps the candidate closer to the origin (the first one on ties).
void keepCloser(SubSimplex& best, bool& have, const SubSimplex& c) {
  if (!have || c.v.squaredNorm() < best.v.squaredNorm()) {
    best = c;
    have = true;
  }
}

// Segment: the origin's projection on the line, with barycentric weights read on the coordinate axis along
// which the segment is longest (the best-conditioned 1-D projection).
SubSimplex s1d(const Vector3d* p, int i0, int i1) {
  const Vector3d& s1 = p[i0];
  const Vector3d& s2 = p[i1];
  const Vector3d t = s2 - s1;
  const double tt = t.squaredNorm();
  if (!(tt > 0)) return single(p, i0);
  const Vector3d p0 = s1 - (s1.dot(t) / tt) * t;
  int I = 0;
  t.cwiseAbs().maxCoeff(&I);
  const double mu = s1[I] - s2[I];
  const double c1 = p0[I] - s2[I];  // mu × weight of s1
  const double c2 = s1[I] - p0[I];  // mu × weight of s2
  if (sameSign(mu, c1) && sameSign(mu, c2)) {
    SubSimplex s;
    s.count = 2;
    s.index[0] = i0;
    s.index[1] = i1;
    const double sum = c1 + c2;
    s.lambda[0] = c1 / sum;
    s.lambda[1] = c2 / sum;
    s.v = p0;  // the projection, orthogonal to the segment to rounding (see s2d)
    return s;
  }
  return single(p, sameSign(mu, c1) ? i0 : i1);
}

// Triangle: project the origin on the plane, then compare signed areas on the coordinate plane where the
// triangle's projection is largest. Edges across which the projection lies are searched recursively.
SubSimplex s2d(const Vector3d* p, int i0, int i1, int i2) {
  const Vector3d& s1 = p[i0];
  const Vector3d& s2 = p[i1];
  const Vector3d& s3 = p[i2];
  const Vector3d n = (s2 - s1).cross(s3 - s1);
  const double nn = n.squaredNorm();
  SubSimplex best;
  bool have = false;
  if (nn > 0) {
    const Vector3d p0 = (s1.dot(n) / nn) * n;
    int J = 0;
    n.cwiseAbs().maxCoeff(&J);
    const int x = (J + 1) % 3, y = (J + 2) % 3;
    auto area = [x, y](const Vector3d& a, const Vector3d& b, const Vector3d& c) {
      return (b[x] - a[x]) * (c[y] - a[y]) - (b[y] - a[y]) * (c[x] - a[x]);
    };
    const double mu = area(s1, s2, s3);
    const double c[3] = {area(p0, s2, s3), area(s1, p0, s3), area(s1, s2, p0)};
    if (sameSign(mu, c[0]) && sameSign(mu, c[1]) && sameSign(mu, c[2])) {
      SubSimplex s;
      s.count = 3;
      s.index[0] = i0;
      s.index[1] = i1;
      s.index[2] = i2;
      const double sum = c[0] + c[1] + c[2];
      for (int k = 0; k < 3; ++k) s.lambda[k] = c[k] / sum;
      // v is the projection itself, not Σ lambda_k s_k: when the origin is 1e-10 from a face whose vertices
      // have coordinates ~1, the combination carries ~1e-16 of rounding sideways, turning v's direction by
      // ~1e-6 rad; p0 is parallel to the face normal, whose direction is set by the (long) edges. (The
      // reported bound and points always come from the lambdas, i.e. from real points of A and B.)
      s.v = p0;
      return s;
    }
    if (!sameSign(mu, c[0])) keepCloser(best, have, s1d(p, i1, i2));
    if (!sameSign(mu, c[1])) keepCloser(best, have, s1d(p, i0, i2));
    if (!sameSign(mu, c[2])) keepCloser(best, have, s1d(p, i0, i1));
    if (have) return best;
  }
  // Collinear or coincident points: the closest point lies on an edge.
  keepCloser(best, have, s1d(p, i0, i1));
  keepCloser(best, have, s1d(p, i0, i2));
  keepCloser(best, have, s1d(p, i1, i2));
  return best;
}

double signedVolume(const Vector3d& a, const Vector3d& b, const Vector3d& c, const Vector3d& d) {
  return (b - a).dot((c - a).cross(d - a));
}

// Tetrahedron: the origin is inside when the four volumes with one vertex replaced by the origin all have the
// sign of the whole; otherwise search the faces it lies beyond.
SubSimplex s3d(const Vector3d* p) {
  const Vector3d o = Vector3d::Zero();
  const double c[4] = {signedVolume(o, p[1], p[2], p[3]), signedVolume(p[0], o, p[2], p[3]),
                       signedVolume(p[0], p[1], o, p[3]), signedVolume(p[0], p[1], p[2], o)};
  const double det = c[0] + c[1] + c[2] + c[3];
  if (sameSign(det, c[0]) && sameSign(det, c[1]) && sameSign(det, c[2]) && sameSign(det, c[3])) {
    SubSimplex s;
    s.count = 4;
    Vector3d v = Vector3d::Zero();
    double size = 0;
    for (int k = 0; k < 4; ++k) {
      s.index[k] = k;
      s.lambda[k] = c[k] / det;
      v += s.lambda[k] * p[k];
      size = std::max(size, p[k].cwiseAbs().maxCoeff());
    }
    // A flat tetrahedron has volumes that are rounding noise, which can agree in sign by chance; then the
    // weights do not reproduce the origin. Accept "inside" only when they do (to a few thousand ulps), else
    // take the closest of all four faces.
    if (v.norm() <= 4096 * std::numeric_limits<double>::epsilon() * size) {
      s.v.setZero();
      return s;
    }
  }
  SubSimplex best;
  bool have = false;
  static const int face[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  for (int j = 0; j < 4; ++j)
    if (!sameSign(det, c[j])) keepCloser(best, have, s2d(p, face[j][0], face[j][1], face[j][2]));
  if (!have)
    for (int j = 0; j < 4; ++j) keepCloser(best, have, s2d(p, face[j][0], face[j][1], face[j][2]));
  return best;
}

}  // namespace

double ConvexScale::roundoff() const { return 8 * kEps * std::max(coordMag, size); }

SupportPoint minkowskiSupport(const SupportFn& a, const SupportFn& b, const Vector3d& d) {
  return minkowskiSupportOf(a, b, d);
}

SubSimplex closestOnSimplex(const Vector3d* points, int n) {
  switch (n) {
    case 1: return single(points, 0);
    case 2: return s1d(points, 0, 1);
    case 3: return s2d(points, 0, 1, 2);
    default: return s3d(points);
  }
}

GjkResult gjk(const SupportFn& a, const SupportFn& b, const SupportPoint& start, double lowerBound, double tolerance,
              int maxIterations, ConvexScale& scale) {
  return gjkLoop(a, b, start, lowerBound, tolerance, maxIterations, scale);
}

ConvexDistance convexDistance(const SupportFn& a, const SupportFn& b, double tolerance, int maxIterations,
                              bool measurePenetration) {
  ConvexDistance out;
  ConvexScale scale;
  // Supports of D = A − B along ±x, ±y, ±z, computed only when needed: they give D's bounding box (its size
  // sets the default tolerance for tolerance <= 0), six separating-axis lower bounds, and seeds for EPA.
  std::vector<SupportPoint> axis;
  double lower = -kInf;
  auto computeAxis = [&]() {
    axis.resize(6);
    Vector3d lo, hi;
    for (int i = 0; i < 3; ++i) {
      const Vector3d e = Vector3d::Unit(i);
      axis[2 * i] = minkowskiSupport(a, b, e);
      axis[2 * i + 1] = minkowskiSupport(a, b, -e);
      hi[i] = axis[2 * i].w[i];
      lo[i] = axis[2 * i + 1].w[i];
      lower = std::max({lower, -hi[i], lo[i]});
      scale.coordMag = std::max({scale.coordMag, gjk_loop::maxAbs(axis[2 * i]), gjk_loop::maxAbs(axis[2 * i + 1])});
    }
    scale.size = (hi - lo).norm();
  };
  if (!(tolerance > 0)) computeAxis();
  const double tol = tolerance > 0 ? tolerance : std::max(1e-15 * scale.size, scale.roundoff());
  maxIterations = std::max(maxIterations, 1);

  // Any point of D starts GJK. (Starting from the support opposite the centre of D's box saves a few
  // iterations on round shapes but costs six support pairs up front: slower overall on boxes and cones.)
  const SupportPoint start = minkowskiSupport(a, b, -Vector3d::UnitX());
  const GjkResult g = gjkWithRestarts(a, b, start, lower, tol, maxIterations, scale, out.iterations);
  lower = g.lowerBound;
  double upper = g.upperBound;
  double witnessGap = g.witnessGap;
  if (g.originInside && !(g.witnessGap <= tol)) {
    // Contact or overlap with the origin in GJK's simplex: pointA = pointB lies in A ∩ B, and such a point is
    // at most the depth (<= −lower) inside either set (a deeper point would overlap B by more than the depth).
    witnessGap = 2 * std::max(0.0, -lower);
  }
  bool useEpa = false;
  EpaResult e;
  if (measurePenetration && (g.originInside || (!g.converged && g.lowerBound < 0))) {
    if (axis.empty()) computeAxis();
    std::vector<SupportPoint> seeds(g.simplex, g.simplex + g.count);
    seeds.insert(seeds.end(), axis.begin(), axis.end());
    e = epa(a, b, seeds, g.count, tol, std::max(maxIterations - g.iterations, 1), scale);
    out.iterations += e.iterations;
    lower = std::max(lower, e.signedLower);
    // EPA's answer when it proves more (always when the sets overlap: its upper bound is then negative), and
    // in contact (GJK's simplex holds the origin): GJK's points coincide there and say nothing about the
    // direction, while EPA's closest face is the contact plane.
    if (e.valid && (e.signedUpper < upper || g.originInside)) {
      useEpa = true;
      upper = std::min(upper, e.signedUpper);
      witnessGap = e.witnessGap;
    }
  }

  if (useEpa) {
    out.distance = e.distance;
    out.normal = e.normal;
    out.pointA = e.pointA;
    out.pointB = e.pointB;
  } else {
    out.distance = (g.pointB - g.pointA).norm();
    out.pointA = g.pointA;
    out.pointB = g.pointB;
    // The normal from v, not from pointB − pointA: the points are combinations of coordinates of the sets'
    // size, so at tiny distances their difference has a noisy direction, while v (a face or edge projection)
    // keeps it.
    // With coinciding points (contact; EPA's polytope was flat) any unit vector is allowed.
    out.normal = g.v.squaredNorm() > 0 ? Vector3d(-g.v.normalized()) : Vector3d::UnitZ();
  }
  // Re-centre the points on the normal (a sideways move of rounding size: ~1e-12 of the sets' size at worst, on
  // sliver simplices) so that pointB − pointA = distance·normal holds to the last bits.
  const Vector3d mid = 0.5 * (out.pointA + out.pointB);
  out.pointA = mid - 0.5 * out.distance * out.normal;
  out.pointB = mid + 0.5 * out.distance * out.normal;
  // The reported value lies in the proved interval; rounding can only widen the interval, never move the value.
  out.distance += 0.0;  // −0 (a zero depth negated) prints as "-0": make it +0
  out.lowerBound = std::min(lower, out.distance);
  out.upperBound = std::max(upper, out.distance);
  out.converged = out.upperBound - out.lowerBound <= tol && witnessGap <= tol;
  return out;
}

}  // namespace unidist::detail
