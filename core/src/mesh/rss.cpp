#include "mesh/rss.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>

namespace unidist::mesh {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

double clampTo(double x, double h) { return std::min(h, std::max(-h, x)); }

/// Extents of the points along the axes, as an RSS (every point straight above or below the rectangle).
Rss fromExtents(const Eigen::Matrix3d& axes, const Eigen::Vector3d& origin, const Eigen::Vector3d& lo,
                const Eigen::Vector3d& hi) {
  Rss r;
  r.axes = axes;
  const Eigen::Vector3d mid = 0.5 * (lo + hi);
  r.center = origin + axes * mid;
  // Pad for the rounding of the projections, of the centre and of the axes' orthonormality (each a few ε of
  // the coordinates involved); growing the radius grows the volume by the same amount in every direction.
  // The sides get the same pad, so the box [±half0, ±half1, ±radius] on the axes holds the points too.
  const double reach = lo.cwiseAbs().sum() + hi.cwiseAbs().sum() + origin.cwiseAbs().sum();
  const double pad = 32.0 * kEps * reach;
  r.half[0] = 0.5 * (hi[0] - lo[0]) + pad;
  r.half[1] = 0.5 * (hi[1] - lo[1]) + pad;
  r.radius = 0.5 * (hi[2] - lo[2]) + pad;
  return r;
}

/// Right-handed orthonormal axes from two directions (e0, then e1 made orthogonal to it); false when they
/// are not finite or nearly parallel.
bool orthonormalFrame(const Eigen::Vector3d& d0, const Eigen::Vector3d& d1, Eigen::Matrix3d& U) {
  const double n0 = d0.norm();
  const Eigen::Vector3d e0 = d0 / n0;
  Eigen::Vector3d e1 = d1 - e0.dot(d1) * e0;
  const double n1 = e1.norm();
  if (!(n1 > 0.5 * d1.norm()) || !e0.allFinite()) return false;
  e1 /= n1;
  U.col(0) = e0;
  U.col(1) = e1;
  U.col(2) = e0.cross(e1);  // unit to a few ε: e0 and e1 are
  return true;
}

/// Unit vector along v when |v| is within 1e-8 of 1 (one Newton step for 1/|v|: error ~ the square of that,
/// below ε), else by a square root.
Eigen::Vector3d nearUnit(const Eigen::Vector3d& v) {
  const double n2 = v.squaredNorm();
  if (std::abs(n2 - 1.0) < 1e-8) return v * (1.5 - 0.5 * n2);
  return v / std::sqrt(n2);
}

/// One Jacobi rotation in the (p, q) plane nearly zeroing A(p, q) of the symmetric A; V accumulates the
/// rotations. The rotation is built from tan(angle / 2) (c = (1 − τ²)/(1 + τ²), s = 2τ/(1 + τ²)), so it is
/// orthogonal to rounding however roughly the angle is taken: for a weak coupling (a near guess, the usual
/// case) by a short series without square roots, else exactly.
void jacobiRotate(Eigen::Matrix3d& A, Eigen::Matrix3d& V, int p, int q) {
  const double apq = A(p, q), app = A(p, p), aqq = A(q, q);
  const double d = aqq - app;
  double tau;  // tan of half the rotation angle
  if (std::abs(apq) <= 0.05 * std::abs(d)) {
    const double x = apq / d, t = x * (1.0 - x * x);  // tan(angle) to O(x⁵)
    tau = t * (0.5 - 0.125 * t * t);
  } else {
    const double g = std::abs(d) + std::sqrt(d * d + 4.0 * apq * apq);
    const double t = (d >= 0 ? 2.0 : -2.0) * apq / g;
    tau = t / (1.0 + std::sqrt(1.0 + t * t));
  }
  if (!std::isfinite(tau)) return;
  const double k = 1.0 / (1.0 + tau * tau);
  const double c = (1.0 - tau * tau) * k, s = 2.0 * tau * k;
  const int r = 3 - p - q;
  A(p, p) = c * c * app - 2.0 * c * s * apq + s * s * aqq;
  A(q, q) = s * s * app + 2.0 * c * s * apq + c * c * aqq;
  A(p, q) = A(q, p) = c * s * (app - aqq) + (c * c - s * s) * apq;
  const double arp = A(r, p), arq = A(r, q);
  A(r, p) = A(p, r) = c * arp - s * arq;
  A(r, q) = A(q, r) = s * arp + c * arq;
  for (int m = 0; m < 3; ++m) {
    const double vp = V(m, p), vq = V(m, q);
    V(m, p) = c * vp - s * vq;
    V(m, q) = s * vp + c * vq;
  }
}

}  // namespace

Eigen::Matrix3d principalAxesFrom(const Eigen::Matrix3d& covariance, const Eigen::Matrix3d& guess) {
  const Eigen::Matrix3d CG = covariance * guess;
  Eigen::Matrix3d A;  // the covariance in the guess's frame (symmetric: six entries)
  for (int p = 0; p < 3; ++p)
    for (int q = p; q < 3; ++q) A(p, q) = A(q, p) = guess.col(p).dot(CG.col(q));
  Eigen::Matrix3d V = guess;
  const auto coupled = [&A](int p, int q) { return std::abs(A(p, q)) > 1e-6 * (std::abs(A(p, p)) + std::abs(A(q, q))); };
  // Weak: a coupling within 0.2 of the variances' gap, so the first-order angle is off by ~0.04 rad at most
  // (0.05 instead: 25–35 % more rotation sweeps and the same node pairs on the linked tori and env/rob, ±0.3 %).
  const auto weak = [&A](int p, int q) { return std::abs(A(p, q)) <= 0.2 * std::abs(A(p, p) - A(q, q)); };
  // A leaf's guess (its first triangle's edge) is often far off in the plane: one exact rotation there.
  if (coupled(0, 1) && !weak(0, 1)) jacobiRotate(A, V, 0, 1);
  Eigen::Matrix3d M = Eigen::Matrix3d::Identity();
  if ((!coupled(0, 1) || weak(0, 1)) && (!coupled(0, 2) || weak(0, 2)) && (!coupled(1, 2) || weak(1, 2))) {
    // Near diagonal (a child's axes for its parent, often): first-order eigenvectors, three independent
    // divisions instead of a chain of rotations; residual couplings of second order, orthonormalised below.
    for (int p = 0; p < 3; ++p)
      for (int q = p + 1; q < 3; ++q)
        if (coupled(p, q)) {
          M(q, p) = A(q, p) / (A(p, p) - A(q, q));
          M(p, q) = -M(q, p);
        }
  } else {
    // One Jacobi sweep: measured on the linked tori and env/rob, more sweeps (converged axes) change the
    // node-pair counts by under 0.1 %.
    if (coupled(0, 1)) jacobiRotate(A, V, 0, 1);
    if (coupled(0, 2)) jacobiRotate(A, V, 0, 2);
    if (coupled(1, 2)) jacobiRotate(A, V, 1, 2);
  }
  int first = 0, second = 1;  // the two largest variances, largest first
  if (A(1, 1) > A(0, 0)) std::swap(first, second);
  if (A(2, 2) > A(second, second)) second = 2;
  if (A(second, second) > A(first, first)) std::swap(first, second);
  const Eigen::Vector3d v0 = V * M.col(first), v1 = V * M.col(second);
  if (!v0.allFinite() || !v1.allFinite()) return guess;
  // Orthonormalised again (Gram–Schmidt): the fit relies on the axes being orthonormal to a few ε, not on
  // them being principal.
  const Eigen::Vector3d e0 = nearUnit(v0);
  const Eigen::Vector3d e1 = nearUnit(v1 - e0.dot(v1) * e0);
  Eigen::Matrix3d U;
  U << e0, e1, e0.cross(e1);
  return U;
}

Eigen::Matrix3d principalAxes(const Eigen::Matrix3d& covariance) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  es.computeDirect(covariance);  // eigenvalues ascending
  Eigen::Matrix3d U = Eigen::Matrix3d::Identity();
  if (es.info() != Eigen::Success || !es.eigenvectors().allFinite()) return U;
  // Orthonormalised again: the fit relies on the axes being orthonormal, not on them being principal.
  if (!orthonormalFrame(es.eigenvectors().col(2), es.eigenvectors().col(1), U)) return Eigen::Matrix3d::Identity();
  return U;
}

Rss fitRss(const Eigen::Vector3d* p, std::size_t n) {
  const Eigen::Vector3d origin = p[0];  // coordinates relative to a point of the set keep small sets precise
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) mean += p[i] - origin;
  mean /= static_cast<double>(n);
  Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d d = p[i] - origin - mean;
    C.noalias() += d * d.transpose();
  }
  return fitRss(principalAxes(C), p, n);
}

Rss fitRss(const Eigen::Matrix3d& axes, const Eigen::Vector3d* p, std::size_t n) {
  // The two side axes as one pair of lanes, the normal apart: the build's hottest loop (every vertex of
  // every node up to 256 triangles), in packed arithmetic without -march flags.
  const Eigen::Vector3d origin = p[0];
  const Eigen::Array2d ax(axes(0, 0), axes(0, 1)), ay(axes(1, 0), axes(1, 1)), az(axes(2, 0), axes(2, 1));
  const double nx = axes(0, 2), ny = axes(1, 2), nz = axes(2, 2);
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Eigen::Array2d lo01 = Eigen::Array2d::Constant(kInf), hi01 = -lo01;
  double lo2 = kInf, hi2 = -kInf;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d d = p[i] - origin;
    const Eigen::Array2d x01 = ax * d.x() + ay * d.y() + az * d.z();
    const double x2 = nx * d.x() + ny * d.y() + nz * d.z();
    lo01 = lo01.min(x01);
    hi01 = hi01.max(x01);
    lo2 = std::min(lo2, x2);
    hi2 = std::max(hi2, x2);
  }
  return fromExtents(axes, origin, Eigen::Vector3d(lo01[0], lo01[1], lo2), Eigen::Vector3d(hi01[0], hi01[1], hi2));
}

Rss mergeRss(const Eigen::Matrix3d& axes, const Rss& a, const Rss& b) {
  // The children's points lie in their boxes [±half0, ±half1, ±radius] on their axes (fromExtents), whose
  // support along an axis u is Σ |u·e_j| half_j: tighter than their RSS (which adds the radius along every
  // axis), and exact when the axes agree.
  const Eigen::Vector3d origin = a.center;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Rss* r : {&a, &b}) {
    const Eigen::Vector3d c = axes.transpose() * (r->center - origin);
    const Eigen::Vector3d box(r->half[0], r->half[1], r->radius);
    const Eigen::Vector3d reach = (axes.transpose() * r->axes).cwiseAbs() * box;
    lo = lo.cwiseMin(c - reach);
    hi = hi.cwiseMax(c + reach);
  }
  return fromExtents(axes, origin, lo, hi);
}

Rss posedRss(const Rss& b, const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  Rss p = b;
  p.center = R * b.center + t;
  p.axes = R * b.axes;
  return p;
}

double rssLowerBound(const Rss& a, const Rss& b, const Eigen::Matrix3d& R, const Eigen::Vector3d& t, double enough) {
  return rssLowerBound(a, posedRss(b, R, t), enough);
}

double rssLowerBound(const Rss& a, const Rss& b, double enough) {
  // Everything in a's rectangle frame: a = [-ha0, ha0] × [-ha1, ha1] × {0}; b = d + s m0 + u m1.
  const Eigen::Matrix3d M = a.axes.transpose() * b.axes;
  const Eigen::Vector3d d = a.axes.transpose() * (b.center - a.center);
  const double ha0 = a.half[0], ha1 = a.half[1], hb0 = b.half[0], hb1 = b.half[1];
  const auto m0 = M.col(0), m1 = M.col(1), m2 = M.col(2);
  const auto gapAlong = [&](const Eigen::Vector3d& u) {
    return std::abs(u.dot(d)) - ha0 * std::abs(u.x()) - ha1 * std::abs(u.y()) - hb0 * std::abs(u.dot(m0)) -
           hb1 * std::abs(u.dot(m1));
  };
  // Along a's normal and along b's normal (orthogonal to b's sides, which then add nothing).
  double gap = std::abs(d.z()) - hb0 * std::abs(m0.z()) - hb1 * std::abs(m1.z());
  gap = std::max(gap, std::abs(m2.dot(d)) - ha0 * std::abs(m2.x()) - ha1 * std::abs(m2.y()));
  const double radii = a.radius + b.radius;
  if (gap - radii >= enough) return gap - radii;
  // Along the direction between a closest-pair estimate: alternating projection from b's centre.
  Eigen::Vector3d q = d, p;
  for (int k = 0; k < 2; ++k) {  // linked tori: 1 step 3.7 % more pairs than 3, 2 steps 0.4 %
    p = Eigen::Vector3d(clampTo(q.x(), ha0), clampTo(q.y(), ha1), 0.0);
    const Eigen::Vector3d w = p - d;
    q = d + clampTo(m0.dot(w), hb0) * m0 + clampTo(m1.dot(w), hb1) * m1;
  }
  const Eigen::Vector3d v = q - p;
  const double len = v.norm();
  if (len > 0) gap = std::max(gap, gapAlong(v / len));
  return gap - radii;
}

}  // namespace unidist::mesh
