#include "nurbs/support_bound.h"

#include "nurbs/bernstein_bound.h"
#include "nurbs/bspline.h"
#include "nurbs/ratio_subdivision.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace unidist::nurbs {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr int kNewtonSteps = 12;

/// Coefficients on the stack for the common degrees (up to a bicubic patch's squared distance, 7 × 7, and a
/// biquadratic one's tube quartic, 9 × 9), on the heap beyond: a certificate is asked of many nodes per query.
class Coefficients {
 public:
  Coefficients() = default;
  Coefficients(const Coefficients&) = delete;
  Coefficients& operator=(const Coefficients&) = delete;
  void assign(std::size_t n, double value) {
    size_ = n;
    if (n > local_.size()) {
      heap_.assign(n, value);
      data_ = heap_.data();
    } else {
      std::fill_n(local_.begin(), n, value);
      data_ = local_.data();
    }
  }
  std::size_t size() const { return size_; }
  double& operator[](std::size_t k) { return data_[k]; }
  double operator[](std::size_t k) const { return data_[k]; }
  const double* begin() const { return data_; }
  const double* end() const { return data_ + size_; }

 private:
  std::array<double, 81> local_;  // up to a biquadratic patch's tube quartic, 9 × 9
  std::vector<double> heap_;
  double* data_ = local_.data();
  std::size_t size_ = 0;
};

/// The Bernstein coefficients (degrees p, q) of a numerator a and a positive denominator w whose ratio g = a / w
/// is maximised: h_c = a − c·w <= 0 wherever g <= c. `error`: how far each a − c·w coefficient may be off,
/// per unit of (|a| + |c|·w) (rounding of their computation).
struct Heights {
  int p = 0, q = 0;
  Coefficients a, w;
  double error = 2 * kEps;

  double coefficient(const Coefficients& c, int i, int j) const { return c[static_cast<std::size_t>(i * (q + 1) + j)]; }
  /// max |a| + |c|·w over the coefficients: the magnitude rounding is measured against.
  double scale(double c) const {
    double s = 0;
    for (std::size_t k = 0; k < a.size(); ++k) s = std::max(s, std::abs(a[k]) + std::abs(c) * w[k]);
    return s;
  }
  /// w at (s, t).
  double denominator(double s, double t) const {
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

/// The maximised g at (s, t) with its gradient and Hessian.
struct Height {
  double g;
  Eigen::Vector2d grad;
  Eigen::Matrix2d hess;
};

/// Is h_c = a − c·w concave over the unit square, but for δ (returned) of rounding? From the Bernstein
/// coefficients of its second derivatives, which bound them over the square.
bool concave(const Heights& h, double c, double& delta) {
  const int p = h.p, q = h.q;
  const auto hc = [&](int i, int j) { return h.coefficient(h.a, i, j) - c * h.coefficient(h.w, i, j); };
  // Each h_c coefficient is off by at most error·scale, so a second-derivative coefficient (weights 1, −2, 1 or
  // ±1 four times, times the degree factor) by at most `err`.
  const double err = 4 * h.error * h.scale(c) * std::max({p * (p - 1), q * (q - 1), p * q});
  double ss = p >= 2 ? -std::numeric_limits<double>::infinity() : 0, tt = q >= 2 ? ss : 0, st = 0;
  for (int i = 0; i + 2 <= p; ++i)
    for (int j = 0; j <= q; ++j) ss = std::max(ss, p * (p - 1) * (hc(i + 2, j) - 2 * hc(i + 1, j) + hc(i, j)));
  for (int i = 0; i <= p; ++i)
    for (int j = 0; j + 2 <= q; ++j) tt = std::max(tt, q * (q - 1) * (hc(i, j + 2) - 2 * hc(i, j + 1) + hc(i, j)));
  for (int i = 0; i < p; ++i)
    for (int j = 0; j < q; ++j)
      st = std::max(st, std::abs(p * q * (hc(i + 1, j + 1) - hc(i + 1, j) - hc(i, j + 1) + hc(i, j))));
  ss += err, tt += err, st += err;
  // Proved negative semidefinite with the rounding counted against it: no allowance. Otherwise the Hessian is
  // allowed δ = 2·err above it (rounding cannot tell a flat direction from a slightly convex one); that adds at
  // most ½δ|y − x0|² <= δ on the unit square.
  delta = 0;
  if (ss <= 0 && tt <= 0 && ss * tt >= st * st) return true;
  delta = 2 * err;
  return ss <= delta && tt <= delta && (delta - ss) * (delta - tt) >= st * st;
}

/// The maximiser of g over [0,1]², by projected Newton from x (where g has its value and derivatives `at`):
/// a local maximiser, the global one where h_c is concave.
template <class HeightAt>
std::pair<Eigen::Vector2d, Height> maximiser(const HeightAt& heightAt, Eigen::Vector2d x, Height at) {
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
    // Halve the step until g does not decrease, but for rounding: near the maximum g is flat to rounding
    // while the gradient, which the bound uses, still shrinks with every Newton step.
    const double noise = 8 * kEps * std::abs(at.g);
    bool accepted = false;
    double moved = 0;
    for (int halving = 0; halving < 8 && !accepted; ++halving, d *= 0.5) {
      const Eigen::Vector2d y = (x + d).cwiseMax(0.0).cwiseMin(1.0);
      const Height next = heightAt(y);
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
  return {x, at};
}

/// max over the square of g = a / w, proved (or not proved) by concavity of h_c at the maximiser; heightAt(x)
/// evaluates g exactly (from the patch, not from a and w).
template <class HeightAt>
SupportBound certifyMaximum(const Heights& h, const HeightAt& heightAt) {
  double wLow = std::numeric_limits<double>::infinity();
  std::size_t highest = 0;
  for (std::size_t k = 0; k < h.w.size(); ++k) {
    if (!std::isfinite(h.a[k]) || !std::isfinite(h.w[k])) return {};
    wLow = std::min(wLow, h.w[k]);
    if (h.a[k] * h.w[highest] > h.a[highest] * h.w[k]) highest = k;
  }
  if (!(wLow > 0)) return {};
  // Concavity for the value at the start (the Greville point of the highest coefficient) first: where it fails
  // (a saddle, a node curving toward the level set) the maximiser is not worth searching for.
  const int i = static_cast<int>(highest) / (h.q + 1), j = static_cast<int>(highest) % (h.q + 1);
  const Eigen::Vector2d start(double(i) / h.p, double(j) / h.q);
  const Height atStart = heightAt(start);
  double delta = 0;
  if (!concave(h, atStart.g, delta)) return {};
  const auto [x0, at] = maximiser(heightAt, start, atStart);
  const double c = at.g;
  if (!std::isfinite(c) || !concave(h, c, delta)) return {};
  // The tangent plane of h_c = w·(g − c) at x0, where g = c: its gradient is w(x0)·∇g. Largest at a corner of
  // the unit square.
  const Eigen::Vector2d grad = h.denominator(x0[0], x0[1]) * at.grad;
  double linear = 0;
  for (double s : {0.0, 1.0})
    for (double t : {0.0, 1.0}) linear = std::max(linear, grad.dot(Eigen::Vector2d(s, t) - x0));
  // h_c(x0) is zero but for rounding, and the tangent plane's gradient is rounded too: a Bernstein sum of
  // (p + 1)(q + 1) terms is off by ~(p + q + 2)·ε·scale, its derivatives by the degree times that; coefficients
  // computed as products (the distance's) add their error beyond the 2ε of a plain one.
  const double scale = h.scale(c);
  const double roundingOfH = (4 * (std::max(h.p, h.q) + 1) * (h.p + h.q + 2) * kEps + (h.error - 2 * kEps)) * scale;
  return {true, c + (linear + delta + roundingOfH) / wLow};
}

}  // namespace

SupportBound certifySupport(const RationalBezierPatch& patch, const Eigen::Vector3d& n) {
  Heights h;
  h.p = patch.degreeU;
  h.q = patch.degreeV;
  h.a.assign(patch.net.size(), 0.0);
  h.w.assign(patch.net.size(), 0.0);
  for (std::size_t k = 0; k < patch.net.size(); ++k) {
    h.a[k] = n.dot(patch.net[k].head<3>());
    h.w[k] = patch.net[k][3];
  }
  return certifyMaximum(h, [&](const Eigen::Vector2d& x) {
    const SurfaceDerivatives d = patch.derivatives(x[0], x[1]);
    Height r;
    r.g = n.dot(d.point);
    r.grad = {n.dot(d.du), n.dot(d.dv)};
    r.hess << n.dot(d.duu), n.dot(d.duv), n.dot(d.duv), n.dot(d.dvv);
    return r;
  });
}

DistanceExtreme certifyDistanceExtreme(const RationalBezierPatch& patch, const Eigen::Vector3d& c, bool farthest,
                                       bool exact, double enough, int halvings) {
  const int n = patch.degreeU, m = patch.degreeV;
  if (2 * std::max(n, m) > kMaxNurbsDegree) return {};  // beyond the Bernstein evaluation's fixed rows
  // ±|X − c·W|² and W² in Bernstein form of degree (2n, 2m) (bernstein_bound.h).
  const double sign = farthest ? 1.0 : -1.0;
  Heights h;
  h.p = 2 * n;
  h.q = 2 * m;
  std::array<Eigen::Vector3d, 16> yLocal;
  std::vector<Eigen::Vector3d> yHeap(patch.net.size() > yLocal.size() ? patch.net.size() : 0);
  Eigen::Vector3d* y = yHeap.empty() ? yLocal.data() : yHeap.data();
  squaredDistanceForm(patch, c, y, h.a, h.w);
  if (!farthest)
    for (std::size_t k = 0; k < h.a.size(); ++k) h.a[k] = -h.a[k];
  double magnitude = 0, weight = 0, reach = 0;  // squared first: one square root each
  for (std::size_t k = 0; k < patch.net.size(); ++k) {
    magnitude = std::max(magnitude, y[k].squaredNorm());
    weight = std::max(weight, patch.net[k][3]);
    reach = std::max(reach, patch.net[k].head<3>().squaredNorm());
  }
  magnitude = std::sqrt(magnitude);
  reach = std::sqrt(reach);
  // Each coefficient is a mean of at most (n + 1)(m + 1) products y·y' (|y| <= magnitude) with rounded weights:
  // off by ((n + 1)(m + 1) + 8)·ε·magnitude²; and y = X − c·W itself is off by ε·(|X| + |c|·W), which moves a
  // product by 2·magnitude times that. Counted per unit of max |a|, which scale(γ) is at least.
  const double absolute =
      kEps * (((n + 1) * (m + 1) + 8) * magnitude * magnitude + 4 * magnitude * (reach + c.norm() * weight));
  h.error = std::max(2 * kEps, absolute / std::max(std::numeric_limits<double>::min(), h.scale(0)));
  // Without concavity the coefficients still bound the ratio: max of ±|S − c|² <= max of the coefficient ratios
  // (second order in the patch size, valid for any patch).
  for (std::size_t k = 0; k < h.a.size(); ++k)
    if (!(h.w[k] > 0) || !std::isfinite(h.a[k])) return {};
  // The ratios in one array pass (vectorised divisions: a certificate is asked of every node a separator meets).
  const auto count = static_cast<Eigen::Index>(h.a.size());
  double ratio = (Eigen::Map<const Eigen::ArrayXd>(h.a.begin(), count) /
                  Eigen::Map<const Eigen::ArrayXd>(h.w.begin(), count)).maxCoeff();
  const double allowance = 2 * h.error * h.scale(0) / *std::min_element(h.w.begin(), h.w.end());
  // A corner's coefficient ratio is the value there: the coefficients' bound within rounding of one is exact (a
  // sphere seen from its centre, at any size), and concavity could prove no more.
  const int corners[4] = {0, h.q, (h.p + 1) * (h.q + 1) - 1 - h.q, (h.p + 1) * (h.q + 1) - 1};
  double cornerHigh = -std::numeric_limits<double>::infinity();
  for (int k : corners) cornerHigh = std::max(cornerHigh, h.a[static_cast<std::size_t>(k)] / h.w[static_cast<std::size_t>(k)]);
  const bool ratioExact = ratio <= cornerHigh + allowance;
  ratio += allowance;
  // The bound of ±|S − c|² that would do: the distance `enough` squared, signed.
  const double enoughSquared = std::isnan(enough) ? ratio : farthest ? enough * enough : -std::max(0.0, enough) * enough;
  const auto subdivided = [&](double upper) {
    if (upper <= enoughSquared) return upper;
    const RatioBound r = subdividedRatioBound(h.p, h.q, h.a.begin(), h.w.begin(),
                                              {enoughSquared, allowance, halvings});
    return std::min(upper, r.upper);
  };
  if (!exact || ratioExact) {
    const double upper = subdivided(ratio);
    return {true, std::sqrt(std::max(0.0, farthest ? upper : -upper))};
  }
  SupportBound b = certifyMaximum(h, [&](const Eigen::Vector2d& x) {
    const SurfaceDerivatives d = patch.derivatives(x[0], x[1]);
    const Eigen::Vector3d r = d.point - c;
    Height out;
    out.g = sign * r.squaredNorm();
    out.grad = 2 * sign * Eigen::Vector2d(r.dot(d.du), r.dot(d.dv));
    const double uv = d.du.dot(d.dv) + r.dot(d.duv);
    out.hess << d.du.squaredNorm() + r.dot(d.duu), uv, uv, d.dv.squaredNorm() + r.dot(d.dvv);
    out.hess *= 2 * sign;
    return out;
  });
  // Proved by concavity, the bound is the maximum to rounding: subdividing cannot improve it.
  const double upper = b.proved ? std::min(b.upper, ratio) : subdivided(ratio);
  // max of ±|S − c|²: the farthest distance is √upper; the nearest is √(−upper) (or 0 when the bound crosses 0).
  if (farthest) return {true, std::sqrt(std::max(0.0, upper))};
  return {true, std::sqrt(std::max(0.0, -upper))};
}

SupportBound certifyPolynomialMaximum(int p, int q, const double* coefficients, double error) {
  if (std::max(p, q) > kMaxNurbsDegree) return {};  // beyond the Bernstein evaluation's fixed rows
  Heights h;
  h.p = p;
  h.q = q;
  const auto count = static_cast<std::size_t>((p + 1) * (q + 1));
  h.a.assign(count, 0.0);
  h.w.assign(count, 1.0);  // the constant 1: the ratio is the polynomial itself
  for (std::size_t k = 0; k < count; ++k) h.a[k] = coefficients[k];
  h.error = std::max(2 * kEps, error);
  return certifyMaximum(h, [&](const Eigen::Vector2d& x) {
    std::array<std::array<double, kMaxNurbsDegree + 1>, 3> bs, bt;
    bernstein(p, x[0], bs);
    bernstein(q, x[1], bt);
    Height out{0, Eigen::Vector2d::Zero(), Eigen::Matrix2d::Zero()};
    for (int i = 0; i <= p; ++i) {
      double row[3] = {0, 0, 0};  // Σ_j B_j^(k)(t) c_ij
      for (int j = 0; j <= q; ++j) {
        const double c = coefficients[i * (q + 1) + j];
        const auto uj = static_cast<std::size_t>(j);
        for (std::size_t k = 0; k < 3; ++k) row[k] += bt[k][uj] * c;
      }
      const auto ui = static_cast<std::size_t>(i);
      out.g += bs[0][ui] * row[0];
      out.grad[0] += bs[1][ui] * row[0];
      out.grad[1] += bs[0][ui] * row[1];
      out.hess(0, 0) += bs[2][ui] * row[0];
      out.hess(0, 1) += bs[1][ui] * row[1];
      out.hess(1, 1) += bs[0][ui] * row[2];
    }
    out.hess(1, 0) = out.hess(0, 1);
    return out;
  });
}

}  // namespace unidist::nurbs
