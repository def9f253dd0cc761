#include "nurbs/support_bound.h"

#include "nurbs/bspline.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace unidist::nurbs {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr int kNewtonSteps = 12;

/// n·X (a) and W (w) of the patch: the Bernstein coefficients of h_c = a − c·w.
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

  /// W at (s, t).
  double weight(double s, double t) const {
    std::array<std::array<double, kMaxNurbsDegree + 1>, 3> bs, bt;
    bernstein(p, s, bs);
    bernstein(q, t, bt);
    double sum = 0;
    for (int i = 0; i <= p; ++i)
      for (int j = 0; j <= q; ++j)
        sum += bs[0][static_cast<std::size_t>(i)] * bt[0][static_cast<std::size_t>(j)] * coefficient(w, i, j);
    return sum;
  }
};

/// g = n·S, its gradient and Hessian at (s, t), from the patch's exact derivatives.
struct Height {
  double g;
  Eigen::Vector2d grad;
  Eigen::Matrix2d hess;
};
Height heightAt(const RationalBezierPatch& patch, const Eigen::Vector3d& n, const Eigen::Vector2d& x) {
  const SurfaceDerivatives d = patch.derivatives(x[0], x[1]);
  Height r;
  r.g = n.dot(d.point);
  r.grad = {n.dot(d.du), n.dot(d.dv)};
  r.hess << n.dot(d.duu), n.dot(d.duv), n.dot(d.duv), n.dot(d.dvv);
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
Eigen::Vector2d maximiser(const RationalBezierPatch& patch, const Eigen::Vector3d& n, Eigen::Vector2d x, Height at) {
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
      const Height next = heightAt(patch, n, y);
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
  const Height atStart = heightAt(patch, n, start);
  double delta = 0;
  if (!concave(h, atStart.g, delta)) return {};
  const Eigen::Vector2d x0 = maximiser(patch, n, start, atStart);
  const Height at = heightAt(patch, n, x0);
  const double c = at.g;
  if (!std::isfinite(c) || !concave(h, c, delta)) return {};
  // The tangent plane of h_c = W·(n·S − c) at x0, where n·S = c: its gradient is W(x0)·∇(n·S). Largest at a
  // corner of the unit square.
  const Eigen::Vector2d grad = h.weight(x0[0], x0[1]) * at.grad;
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
