#include "nurbs/support_bound.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace unidist::nurbs {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr int kNewtonSteps = 12;
using Basis = std::array<double, kMaxNurbsDegree + 1>;

/// Bernstein polynomials of degree p at x and their first and second derivatives (entries 0..p).
void basis(int p, double x, Basis& b0, Basis& b1, Basis& b2) {
  // Degrees 0 up to p in place in b0, degrees p − 1 and p − 2 copied on the way: the derivatives are made of
  // them. They are kept shifted by one and two places with zeros around, so B_k outside 0..degree reads zero.
  const std::size_t n = static_cast<std::size_t>(p);
  std::array<double, kMaxNurbsDegree + 3> lower1, lower2;  // lower1[k + 1] = B_k^(p−1), lower2[k + 2] = B_k^(p−2)
  std::fill_n(lower1.begin(), n + 2, 0.0);
  std::fill_n(lower2.begin(), n + 3, 0.0);
  b0[0] = 1;
  if (n == 1) lower1[1] = 1;
  if (n == 2) lower2[2] = 1;
  for (std::size_t d = 1; d <= n; ++d) {
    b0[d] = x * b0[d - 1];
    for (std::size_t k = d - 1; k > 0; --k) b0[k] = (1 - x) * b0[k] + x * b0[k - 1];
    b0[0] *= 1 - x;
    if (d + 1 == n) std::copy_n(b0.begin(), d + 1, lower1.begin() + 1);
    if (d + 2 == n) std::copy_n(b0.begin(), d + 1, lower2.begin() + 2);
  }
  for (std::size_t k = 0; k <= n; ++k) {
    b1[k] = p * (lower1[k] - lower1[k + 1]);
    b2[k] = p * (p - 1) * (lower2[k] - 2 * lower2[k + 1] + lower2[k + 2]);
  }
}

/// A scalar tensor-product polynomial and its derivatives up to order two at one point.
struct Jet {
  double f = 0, fs = 0, ft = 0, fss = 0, fst = 0, ftt = 0;
};

/// n·X (a) and W (w) of the patch.
struct Heights {
  int p, q;
  std::vector<double> a, w;

  Heights(const RationalBezierPatch& patch, const Eigen::Vector3d& n) : p(patch.degreeU), q(patch.degreeV) {
    a.reserve(patch.net.size());
    w.reserve(patch.net.size());
    for (const Eigen::Vector4d& h : patch.net) {
      a.push_back(n.dot(h.head<3>()));
      w.push_back(h[3]);
    }
  }
  double coefficient(const std::vector<double>& c, int i, int j) const { return c[static_cast<std::size_t>(i * (q + 1) + j)]; }

  void evaluate(double s, double t, Jet& A, Jet& W) const {
    Basis s0, s1, s2, t0, t1, t2;
    basis(p, s, s0, s1, s2);
    basis(q, t, t0, t1, t2);
    A = {};
    W = {};
    // Each row contracted along t (value, first, second derivative), then the rows along s.
    for (std::size_t i = 0; i <= static_cast<std::size_t>(p); ++i) {
      const std::size_t row = i * static_cast<std::size_t>(q + 1);
      double a0 = 0, a1 = 0, a2 = 0, w0 = 0, w1 = 0, w2 = 0;
      for (std::size_t j = 0; j <= static_cast<std::size_t>(q); ++j) {
        const double ca = a[row + j], cw = w[row + j];
        a0 += ca * t0[j], a1 += ca * t1[j], a2 += ca * t2[j];
        w0 += cw * t0[j], w1 += cw * t1[j], w2 += cw * t2[j];
      }
      A.f += s0[i] * a0, A.fs += s1[i] * a0, A.fss += s2[i] * a0, A.ft += s0[i] * a1, A.fst += s1[i] * a1, A.ftt += s0[i] * a2;
      W.f += s0[i] * w0, W.fs += s1[i] * w0, W.fss += s2[i] * w0, W.ft += s0[i] * w1, W.fst += s1[i] * w1, W.ftt += s0[i] * w2;
    }
  }
};

/// g = A / W, its gradient and Hessian, from the jets (quotient rule).
struct Quotient {
  double g;
  Eigen::Vector2d grad;
  Eigen::Matrix2d hess;
};
Quotient quotient(const Jet& A, const Jet& W) {
  Quotient r;
  r.g = A.f / W.f;
  const double gs = (A.fs - r.g * W.fs) / W.f, gt = (A.ft - r.g * W.ft) / W.f;
  r.grad = {gs, gt};
  const double gss = (A.fss - 2 * gs * W.fs - r.g * W.fss) / W.f;
  const double gtt = (A.ftt - 2 * gt * W.ft - r.g * W.ftt) / W.f;
  const double gst = (A.fst - gs * W.ft - gt * W.fs - r.g * W.fst) / W.f;
  r.hess << gss, gst, gst, gtt;
  return r;
}

/// The larger degree.
int largerDegree(const Heights& h) { return std::max(h.p, h.q); }

/// The Greville point of the highest control point: where the maximiser search starts.
Eigen::Vector2d highestGreville(const Heights& h) {
  std::size_t best = 0;
  for (std::size_t k = 1; k < h.a.size(); ++k)
    if (h.a[k] / h.w[k] > h.a[best] / h.w[best]) best = k;
  const int i = static_cast<int>(best) / (h.q + 1), j = static_cast<int>(best) % (h.q + 1);
  return {double(i) / h.p, double(j) / h.q};
}

/// Is h_c = a − c·w concave over the unit square, but for δ (returned) of rounding? From the Bernstein
/// coefficients of its second derivatives, which bound them over the square.
bool concave(const Heights& h, double c, double& delta) {
  const int p = h.p, q = h.q;
  double scale = 0;
  for (std::size_t k = 0; k < h.a.size(); ++k) scale = std::max(scale, std::abs(h.a[k]) + std::abs(c) * h.w[k]);
  const auto hc = [&](int i, int j) { return h.coefficient(h.a, i, j) - c * h.coefficient(h.w, i, j); };
  // Each h_c coefficient is off by at most 2ε·scale, so a second-derivative coefficient (weights 1, −2, 1 or
  // ±1 four times, times the degree factor) by at most `err`.
  const double err = 8 * kEps * scale * std::max({p * (p - 1), q * (q - 1), p * q});
  double ss = p >= 2 ? -std::numeric_limits<double>::infinity() : 0, tt = q >= 2 ? ss : 0, st = 0;
  for (int i = 0; i + 2 <= p; ++i)
    for (int j = 0; j <= q; ++j) ss = std::max(ss, p * (p - 1) * (hc(i + 2, j) - 2 * hc(i + 1, j) + hc(i, j)));
  for (int i = 0; i <= p; ++i)
    for (int j = 0; j + 2 <= q; ++j) tt = std::max(tt, q * (q - 1) * (hc(i, j + 2) - 2 * hc(i, j + 1) + hc(i, j)));
  for (int i = 0; i < p; ++i)
    for (int j = 0; j < q; ++j)
      st = std::max(st, std::abs(p * q * (hc(i + 1, j + 1) - hc(i + 1, j) - hc(i, j + 1) + hc(i, j))));
  // The Hessian is allowed δ = 2·err above negative semidefinite (rounding cannot tell a flat direction from a
  // slightly convex one); that adds at most ½δ|y − x0|² <= δ on the unit square.
  delta = 2 * err;
  ss += err, tt += err, st += err;
  return ss <= delta && tt <= delta && (delta - ss) * (delta - tt) >= st * st;
}

/// The maximiser of n·S over [0,1]², by projected Newton from x (where n·S has its value and derivatives `at`):
/// a local maximiser, the global one where h_c is concave.
Eigen::Vector2d maximiser(const Heights& h, Eigen::Vector2d x, Quotient at) {
  Jet A, W;
  for (int step = 0; step < kNewtonSteps; ++step) {
    // Coordinates held at a bound the gradient pushes against stay there.
    Eigen::Vector2d d = Eigen::Vector2d::Zero();
    bool free[2];
    for (int c = 0; c < 2; ++c)
      free[c] = !((x[c] <= 0 && at.grad[c] < 0) || (x[c] >= 1 && at.grad[c] > 0));
    if (free[0] && free[1] && at.hess(0, 0) < 0 && at.hess.determinant() > 0) {
      d = -at.hess.inverse() * at.grad;
    } else {  // one coordinate held, or a singular Hessian (a flat direction): Newton per coordinate
      for (int c = 0; c < 2; ++c)
        if (free[c] && at.hess(c, c) < 0) d[c] = -at.grad[c] / at.hess(c, c);
    }
    if (d.squaredNorm() == 0) {  // not concave here: a gradient step
      for (int c = 0; c < 2; ++c)
        if (free[c]) d[c] = at.grad[c];
      const double norm = d.norm();
      if (norm == 0) break;
      d *= 0.25 / norm;
    }
    // Halve the step until n·S does not decrease, but for rounding: near the maximum n·S is flat to rounding
    // while the gradient, which the bound uses, still shrinks with every Newton step.
    const double noise = 8 * kEps * std::abs(at.g);
    bool accepted = false;
    double moved = 0;
    for (int halving = 0; halving < 8 && !accepted; ++halving, d *= 0.5) {
      const Eigen::Vector2d y = (x + d).cwiseMax(0.0).cwiseMin(1.0);
      h.evaluate(y[0], y[1], A, W);
      const Quotient next = quotient(A, W);
      if (next.g >= at.g - noise) {
        accepted = true;
        moved = (y - x).cwiseAbs().maxCoeff();
        x = y;
        at = next;
      }
    }
    // Newton converges quadratically: after a step this short the next would move x by ~its square.
    if (!accepted || moved <= 1e-9) break;
  }
  return x;
}

}  // namespace

SupportBound certifySupport(const RationalBezierPatch& patch, const Eigen::Vector3d& n) {
  const Heights h(patch, n);
  double wLow = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < h.w.size(); ++k) {
    if (!std::isfinite(h.a[k]) || !std::isfinite(h.w[k])) return {};
    wLow = std::min(wLow, h.w[k]);
  }
  if (!(wLow > 0)) return {};
  // Concavity for the value at the start first: where it fails (a saddle, a node curving toward the plane)
  // the maximiser is not worth searching for.
  const Eigen::Vector2d start = highestGreville(h);
  Jet A, W;
  h.evaluate(start[0], start[1], A, W);
  double delta = 0;
  if (!concave(h, A.f / W.f, delta)) return {};
  const Eigen::Vector2d x0 = maximiser(h, start, quotient(A, W));
  h.evaluate(x0[0], x0[1], A, W);
  const double c = A.f / W.f;
  if (!std::isfinite(c) || !concave(h, c, delta)) return {};
  // The tangent plane of h_c at x0, largest at a corner of the unit square.
  const Eigen::Vector2d grad(A.fs - c * W.fs, A.ft - c * W.ft);
  double linear = 0;
  for (double s : {0.0, 1.0})
    for (double t : {0.0, 1.0}) linear = std::max(linear, grad.dot(Eigen::Vector2d(s, t) - x0));
  double scale = 0;
  for (std::size_t k = 0; k < h.a.size(); ++k) scale = std::max(scale, std::abs(h.a[k]) + std::abs(c) * h.w[k]);
  // h_c(x0) is zero but for rounding, and the tangent plane's gradient is rounded too: a Bernstein sum of
  // (p + 1)(q + 1) terms is off by ~(p + q + 2)·ε·scale, its derivatives by the degree times that.
  const double roundingOfH = 4 * (largerDegree(h) + 1) * (h.p + h.q + 2) * kEps * scale;
  return {true, c + (linear + delta + roundingOfH) / wLow};
}

}  // namespace unidist::nurbs
