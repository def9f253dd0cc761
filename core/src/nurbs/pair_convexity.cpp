#include "nurbs/pair_convexity.h"

#include "nurbs/binomial.h"
#include "nurbs/interval.h"
#include "nurbs/patch_tree.h"
#include "nurbs/small_ldlt.h"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <limits>

namespace unidist::nurbs {
namespace {

constexpr int kOrder = 3;  // the mean-value form of the Hessian needs third derivatives
constexpr double kRounding = 256 * std::numeric_limits<double>::epsilon();

/// S_(i,j) = ∂^(i+j) S / ∂s^i ∂t^j for i + j <= 3: enclosures over a box, or values at a point (zero width).
using Derivatives = std::array<std::array<IntervalVec3, kOrder + 1>, kOrder + 1>;
/// The same of the homogeneous (X, W).
using HomogeneousDerivatives = std::array<std::array<std::array<Interval, 4>, kOrder + 1>, kOrder + 1>;

/// The patch's homogeneous derivatives (X, W)_(i,j), i + j <= 3, in Bernstein form: net (i, j) is the (i, j)-th
/// forward difference of the control net times n!/(n−i)!·m!/(m−j)!, of degree (n − i, m − j).
class DifferenceNets {
 public:
  explicit DifferenceNets(const RationalBezierPatch& p) : n_(p.degreeU), m_(p.degreeV) {
    net_[0][0] = p.net;
    for (int i = 0; i <= std::min(kOrder, n_); ++i)
      for (int j = 0; i + j <= kOrder && j <= m_; ++j) {
        if (i == 0 && j == 0) continue;
        // Differentiate the previous net along u (j == 0) or along v.
        const bool alongU = j == 0;
        const int pi = alongU ? i - 1 : i, pj = alongU ? j : j - 1;
        const int degree = alongU ? n_ - pi : m_ - pj;
        auto& out = net_[index(i)][index(j)];
        out.resize(static_cast<std::size_t>((n_ - i + 1) * (m_ - j + 1)));
        for (int a = 0; a <= n_ - i; ++a)
          for (int b = 0; b <= m_ - j; ++b)
            out[static_cast<std::size_t>(a * (m_ - j + 1) + b)] =
                degree * (alongU ? at(pi, pj, a + 1, b) - at(pi, pj, a, b) : at(pi, pj, a, b + 1) - at(pi, pj, a, b));
      }
  }

  /// Ranges of (X, W)_(i,j) over the whole patch: a Bernstein polynomial lies within its coefficients' range.
  HomogeneousDerivatives ranges() const {
    HomogeneousDerivatives H{};
    forEachDerivative([&](int i, int j) {
      auto& range = H[index(i)][index(j)];
      const auto& net = net_[index(i)][index(j)];
      for (int q = 0; q < 4; ++q) {
        double lo = net[0][q], hi = lo;
        for (const Eigen::Vector4d& c : net) lo = std::min(lo, c[q]), hi = std::max(hi, c[q]);
        range[static_cast<std::size_t>(q)] = {lo, hi};
      }
    });
    return H;
  }

  /// Values of (X, W)_(i,j), i + j <= maxOrder, at (s, t) (zero-width intervals; higher orders left zero).
  HomogeneousDerivatives values(double s, double t, int maxOrder) const {
    std::array<std::array<double, kMaxNurbsDegree + 1>, kMaxNurbsDegree + 1> bu{}, bv{};
    basis(n_, s, bu);
    basis(m_, t, bv);
    HomogeneousDerivatives H{};
    forEachDerivative([&](int i, int j) {
      if (i + j > maxOrder) return;
      Eigen::Vector4d v = Eigen::Vector4d::Zero();
      for (int a = 0; a <= n_ - i; ++a) {
        Eigen::Vector4d row = Eigen::Vector4d::Zero();
        for (int b = 0; b <= m_ - j; ++b) row += bv[index(m_ - j)][index(b)] * at(i, j, a, b);
        v += bu[index(n_ - i)][index(a)] * row;
      }
      for (int q = 0; q < 4; ++q) H[index(i)][index(j)][static_cast<std::size_t>(q)] = {v[q], v[q]};
    });
    return H;
  }

 private:
  static std::size_t index(int k) { return static_cast<std::size_t>(k); }

  const Eigen::Vector4d& at(int i, int j, int a, int b) const {
    return net_[index(i)][index(j)][static_cast<std::size_t>(a * (m_ - j + 1) + b)];
  }

  template <typename F>
  void forEachDerivative(F&& f) const {
    for (int i = 0; i <= std::min(kOrder, n_); ++i)
      for (int j = 0; i + j <= kOrder && j <= m_; ++j) f(i, j);
  }

  /// Bernstein polynomials of every degree up to `degree` at x: out[d][k] = B_k^d(x).
  static void basis(int degree, double x, std::array<std::array<double, kMaxNurbsDegree + 1>, kMaxNurbsDegree + 1>& out) {
    out[0][0] = 1;
    for (int d = 1; d <= degree; ++d) {
      out[index(d)][0] = (1 - x) * out[index(d - 1)][0];
      for (int k = 1; k < d; ++k)
        out[index(d)][index(k)] = (1 - x) * out[index(d - 1)][index(k)] + x * out[index(d - 1)][index(k - 1)];
      out[index(d)][index(d)] = x * out[index(d - 1)][index(d - 1)];
    }
  }

  int n_, m_;
  std::array<std::array<std::vector<Eigen::Vector4d>, kOrder + 1>, kOrder + 1> net_;
};

/// S_(i,j) from X = W·S by Leibniz: S_α = (X_α − Σ_{0<β<=α} C(α,β) W_β S_(α−β)) / W, from S itself. False for a
/// weight range that is not positive.
bool rationalDerivatives(const HomogeneousDerivatives& H, const IntervalVec3& point, Derivatives& S,
                         int maxOrder = kOrder) {
  const Interval W = H[0][0][3];
  if (!(W.lo > 0)) return false;
  S[0][0] = point;
  for (int order = 1; order <= maxOrder; ++order)
    for (int i = 0; i <= order; ++i) {
      const int j = order - i;
      const auto& X = H[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
      IntervalVec3 acc{X[0], X[1], X[2]};
      for (int k = 0; k <= i; ++k)
        for (int l = 0; l <= j; ++l) {
          if (k == 0 && l == 0) continue;
          const Interval w = (binomial(i, k) * binomial(j, l)) * H[static_cast<std::size_t>(k)][static_cast<std::size_t>(l)][3];
          acc = acc - w * S[static_cast<std::size_t>(i - k)][static_cast<std::size_t>(j - l)];
        }
      for (Interval& c : acc) c = dividedByPositive(c, W);
      S[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = acc;
    }
  return true;
}

/// Enclosures over a whole patch, with respect to the parameters of the patch it was cut from (box widths ws, wt).
bool encloseOver(const RationalBezierPatch& p, double ws, double wt, Derivatives& S) {
  // The point itself: the Euclidean control points' box (convex hull), tighter than X / W.
  Eigen::Vector3d lo = p.point(0, 0), hi = lo;
  for (int i = 0; i <= p.degreeU; ++i)
    for (int j = 0; j <= p.degreeV; ++j) {
      lo = lo.cwiseMin(p.point(i, j));
      hi = hi.cwiseMax(p.point(i, j));
    }
  if (!rationalDerivatives(DifferenceNets(p).ranges(), {Interval{lo[0], hi[0]}, {lo[1], hi[1]}, {lo[2], hi[2]}}, S)) return false;
  // The chain rule's factors 1 / (ws^i wt^j), by products (std::pow costs more than the rest of the loop).
  double perS = 1;
  for (int i = 0; i <= kOrder; ++i, perS /= ws) {
    double factor = perS;
    for (int j = 0; i + j <= kOrder; ++j, factor /= wt)
      for (Interval& c : S[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)]) c = factor * c;
  }
  return true;
}

/// S and its derivatives up to maxOrder at (s, t).
bool valuesAt(const DifferenceNets& p, double s, double t, Derivatives& S, int maxOrder = kOrder) {
  const HomogeneousDerivatives H = p.values(s, t, maxOrder);
  const double w = H[0][0][3].lo;
  IntervalVec3 point;
  for (std::size_t q = 0; q < 3; ++q) point[q] = {H[0][0][q].lo / w, H[0][0][q].lo / w};
  return rationalDerivatives(H, point, S, maxOrder);
}

RationalBezierPatch mapped(RationalBezierPatch p, const Eigen::Isometry3d& X) {
  for (Eigen::Vector4d& h : p.net) h.head<3>() = X.linear() * h.head<3>() + h[3] * X.translation();
  return p;
}

/// r = S_A(s,t) − S_B(u,v) and its derivatives up to order three in the variables (0, 1: A's s, t; 2, 3: B's
/// u, v), tabulated once: mixed A–B derivatives vanish.
struct Residual {
  IntervalVec3 r;
  std::array<IntervalVec3, 4> d1{};
  std::array<std::array<IntervalVec3, 4>, 4> d2{};
  std::array<std::array<std::array<IntervalVec3, 4>, 4>, 4> d3{};

  Residual(const Derivatives& A, const Derivatives& B, int maxOrder = kOrder) : r(A[0][0] - B[0][0]) {
    // The derivative by the variables with s-count i and t-count j, all on one side (+A or −B).
    const auto side = [&](int v, int i, int j) {
      const auto& D = v < 2 ? A : B;
      const IntervalVec3& x = D[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
      return v < 2 ? x : -x;
    };
    const auto st = [](int v) { return v % 2 == 0 ? std::array<int, 2>{1, 0} : std::array<int, 2>{0, 1}; };
    for (int p = 0; p < 4; ++p) {
      const auto [ps, pt] = st(p);
      d1[idx(p)] = side(p, ps, pt);
      if (maxOrder < 2) continue;
      for (int q = 0; q < 4; ++q) {
        if ((p < 2) != (q < 2)) continue;
        const auto [qs, qt] = st(q);
        d2[idx(p)][idx(q)] = side(p, ps + qs, pt + qt);
        if (maxOrder < 3) continue;
        for (int c = 0; c < 4; ++c) {
          if ((p < 2) != (c < 2)) continue;
          const auto [cs, ct] = st(c);
          d3[idx(p)][idx(q)][idx(c)] = side(p, ps + qs + cs, pt + qt + ct);
        }
      }
    }
  }

  static std::size_t idx(int k) { return static_cast<std::size_t>(k); }
};

Eigen::Vector3d mid(const IntervalVec3& v) { return {0.5 * (v[0].lo + v[0].hi), 0.5 * (v[1].lo + v[1].hi), 0.5 * (v[2].lo + v[2].hi)}; }

/// max over the boxes of |a·b − a(x)·b(x)|: (a − a(x))·b + a(x)·(b − b(x)), componentwise magnitudes.
double dotDeviation(const IntervalVec3& a, const IntervalVec3& ax, const IntervalVec3& b, const IntervalVec3& bx) {
  double sum = 0;
  for (std::size_t i = 0; i < 3; ++i) sum += (a[i] - ax[i]).magnitude() * b[i].magnitude() + ax[i].magnitude() * (b[i] - bx[i]).magnitude();
  return sum;
}

/// Upper bound of the spectral radius of a non-negative symmetric matrix.
double spectralBound(const Eigen::Matrix4d& m) { return std::min(m.rowwise().sum().maxCoeff(), m.norm()); }

/// Over the box, where f = ½|S_A − S_B|² is convex: |S_A − S_B| >= sqrt(2 (f(z) + min over the box of g(z)·(y − z))),
/// less rounding (each factor's coordinates to kRounding of `scale`); `at` holds the derivatives at z.
double tangentBound(const Residual& at, const Eigen::Vector4d& lo, const Eigen::Vector4d& hi, const Eigen::Vector4d& z,
                    double scale) {
  const Eigen::Vector3d r = mid(at.r);
  double f = 0.5 * r.squaredNorm();
  for (int c = 0; c < 4; ++c) {
    const Eigen::Vector3d J = mid(at.d1[static_cast<std::size_t>(c)]);
    const double g = r.dot(J), slack = kRounding * scale * J.norm();
    f += std::min(g * (lo[c] - z[c]), g * (hi[c] - z[c])) - slack * std::max(z[c] - lo[c], hi[c] - z[c]);
  }
  return std::max(0.0, std::sqrt(2 * std::max(0.0, f)) - kRounding * scale);
}

}  // namespace

ConvexityCertificate certifyConvexPair(const RationalBezierPatch& a, const RationalBezierPatch& b,
                                       const Eigen::Isometry3d& X_AB, const Eigen::Vector4d& lo,
                                       const Eigen::Vector4d& hi, const Eigen::Vector4d& x) {
  ConvexityCertificate out;
  out.ratio = std::numeric_limits<double>::infinity();
  const Eigen::Vector4d width = hi - lo;
  if (!(width.minCoeff() > 0)) return out;
  // Both patches in a frame centred between the two points at x: the rational quotient's interval terms carry
  // the coordinates' size (X_α − W_α·S ...), so far from the origin they would swamp the derivatives.
  const Eigen::Vector3d centre = 0.5 * (a.evaluate(x[0], x[1]) + X_AB * b.evaluate(x[2], x[3]));
  const Eigen::Isometry3d toCentre(Eigen::Translation3d(-centre));
  const RationalBezierPatch aC = mapped(a, toCentre), bC = mapped(b, toCentre * X_AB);
  const DifferenceNets netsA(aC), netsB(bC);
  Derivatives boxA, boxB, atA, atB;
  if (!encloseOver(subpatch(aC, lo[0], hi[0], lo[1], hi[1]), width[0], width[1], boxA) ||
      !encloseOver(subpatch(bC, lo[2], hi[2], lo[3], hi[3]), width[2], width[3], boxB) ||
      !valuesAt(netsA, x[0], x[1], atA) || !valuesAt(netsB, x[2], x[3], atB))
    return out;
  const Residual box(boxA, boxB), at(atA, atB);
  const auto u = [](int k) { return static_cast<std::size_t>(k); };

  // f, its gradient and Hessian at x: H_pq = r_p·r_q + r·r_pq.
  const Eigen::Vector3d r = mid(at.r);
  std::array<Eigen::Vector3d, 4> J;
  std::array<std::array<Eigen::Vector3d, 4>, 4> K;
  for (int p = 0; p < 4; ++p) {
    J[u(p)] = mid(at.d1[u(p)]);
    for (int q = 0; q < 4; ++q) K[u(p)][u(q)] = mid(at.d2[u(p)][u(q)]);
  }
  Eigen::Matrix4d Hx;
  Eigen::Vector4d g;
  for (int p = 0; p < 4; ++p) {
    g[p] = r.dot(J[u(p)]);
    for (int q = 0; q < 4; ++q) Hx(p, q) = J[u(p)].dot(J[u(q)]) + r.dot(K[u(p)][u(q)]);
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eigen(Hx);
  if (!(eigen.eigenvalues()[0] > 0)) return out;
  // H(y) = H(x) + E is positive definite when ||P E P|| < 1, P = H(x)^(-1/2) (P H(y) P = I + P E P).
  const Eigen::Matrix4d P = eigen.eigenvectors() * eigen.eigenvalues().cwiseInverse().cwiseSqrt().asDiagonal() *
                            eigen.eigenvectors().transpose();
  // E = Σ_c ∫ (y_c − x_c) ∂_c H: ||P E P|| <= Σ_c reach_c (||P ∂_c H(x) P|| + ||P (∂_c H(z) − ∂_c H(x)) P||), with
  // ∂_c H_pq = r_pc·r_q + r_p·r_qc + r_c·r_pq + r·r_pqc, its deviation over the box enclosed product by product.
  const Eigen::Vector4d reach = (x - lo).cwiseMax(hi - x);
  double relative = 0;
  for (int c = 0; c < 4; ++c) {
    Eigen::Matrix4d dH, deviation;
    for (int p = 0; p < 4; ++p)
      for (int q = p; q < 4; ++q) {
        const std::size_t pi = u(p), qi = u(q), ci = u(c);
        const Eigen::Vector3d T = mid(at.d3[pi][qi][ci]);
        dH(p, q) = dH(q, p) = K[pi][ci].dot(J[qi]) + J[pi].dot(K[qi][ci]) + J[ci].dot(K[pi][qi]) + r.dot(T);
        deviation(p, q) = deviation(q, p) =
            dotDeviation(box.d2[pi][ci], at.d2[pi][ci], box.d1[qi], at.d1[qi]) +
            dotDeviation(box.d1[pi], at.d1[pi], box.d2[qi][ci], at.d2[qi][ci]) +
            dotDeviation(box.d1[ci], at.d1[ci], box.d2[pi][qi], at.d2[pi][qi]) +
            dotDeviation(box.r, at.r, box.d3[pi][qi][ci], at.d3[pi][qi][ci]);
      }
    const double pointPart = (P * dH * P).cwiseAbs().rowwise().sum().maxCoeff();  // >= its spectral norm
    relative += reach[c] * (pointPart + spectralBound(P.cwiseAbs() * deviation * P.cwiseAbs()));
  }
  // P H(x) P is I only up to the eigen-decomposition's rounding: its residual counts against the margin too, and
  // so does the rounding of H(x) itself and of the sums above.
  relative += (P * Hx * P - Eigen::Matrix4d::Identity()).cwiseAbs().rowwise().sum().maxCoeff();
  relative += spectralBound(P.cwiseAbs() * Eigen::Matrix4d::Constant(1e-12 * Hx.cwiseAbs().maxCoeff()) * P.cwiseAbs());
  out.ratio = relative;
  if (!(out.ratio < 1)) return out;

  // Convex: f(y) >= f(z) + g(z)·(y − z) on the box for every z in it. Newton's end is stationary only to the
  // resolution of its descent test, so z is x after up to two plain Newton steps (kept in the box).
  const double scale = centre.cwiseAbs().maxCoeff() + r.norm();
  // Each point is evaluated once: its derivatives give both its bound and the next step's gradient.
  const SmallLdlt<4> solver(Hx);
  double lower = tangentBound(at, lo, hi, x, scale);
  Eigen::Vector4d z = x, gz = g;
  Derivatives zA, zB;
  for (int step = 0; step < 2; ++step) {
    z = (z - solver.solve(gz)).cwiseMax(lo).cwiseMin(hi);
    // Only the value and the gradient are needed there.
    if (!valuesAt(netsA, z[0], z[1], zA, 1) || !valuesAt(netsB, z[2], z[3], zB, 1)) break;
    const Residual atZ(zA, zB, 1);
    lower = std::max(lower, tangentBound(atZ, lo, hi, z, scale));
    const Eigen::Vector3d rz = mid(atZ.r);
    for (int c = 0; c < 4; ++c) gz[c] = rz.dot(mid(atZ.d1[u(c)]));
  }
  out.proved = true;
  out.lower = lower;
  return out;
}

}  // namespace unidist::nurbs
