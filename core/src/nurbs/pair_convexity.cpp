#include "nurbs/pair_convexity.h"

#include "nurbs/binomial.h"
#include "nurbs/interval.h"
#include "nurbs/patch_tree.h"

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

double fallingFactorial(int n, int k) {
  double f = 1;
  for (int q = 0; q < k; ++q) f *= n - q;
  return f;
}

/// Bernstein coefficient (a, b) of the homogeneous derivative (X, W)_(i,j): the (i, j)-th forward difference of
/// the net times n!/(n−i)!·m!/(m−j)!.
Eigen::Vector4d differenceCoefficient(const RationalBezierPatch& p, int i, int j, int a, int b) {
  Eigen::Vector4d c = Eigen::Vector4d::Zero();
  for (int k = 0; k <= i; ++k)
    for (int l = 0; l <= j; ++l) {
      const double sign = ((i - k + j - l) % 2 == 0) ? 1.0 : -1.0;
      c += sign * binomial(i, k) * binomial(j, l) * p.at(a + k, b + l);
    }
  return fallingFactorial(p.degreeU, i) * fallingFactorial(p.degreeV, j) * c;
}

/// Over the whole patch: a Bernstein polynomial lies within its coefficients' range.
HomogeneousDerivatives homogeneousRanges(const RationalBezierPatch& p) {
  HomogeneousDerivatives H{};
  for (int i = 0; i <= std::min(kOrder, p.degreeU); ++i)
    for (int j = 0; i + j <= kOrder && j <= p.degreeV; ++j) {
      auto& range = H[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
      for (int a = 0; a + i <= p.degreeU; ++a)
        for (int b = 0; b + j <= p.degreeV; ++b) {
          const Eigen::Vector4d c = differenceCoefficient(p, i, j, a, b);
          for (int q = 0; q < 4; ++q) {
            Interval& r = range[static_cast<std::size_t>(q)];
            r = (a == 0 && b == 0) ? Interval{c[q], c[q]} : Interval{std::min(r.lo, c[q]), std::max(r.hi, c[q])};
          }
        }
    }
  return H;
}

/// At (s, t): the difference nets summed with the Bernstein basis of their degrees.
HomogeneousDerivatives homogeneousValues(const RationalBezierPatch& p, double s, double t) {
  const auto bernstein = [](int n, int k, double x) {
    return binomial(n, k) * std::pow(x, k) * std::pow(1 - x, n - k);
  };
  HomogeneousDerivatives H{};
  for (int i = 0; i <= std::min(kOrder, p.degreeU); ++i)
    for (int j = 0; i + j <= kOrder && j <= p.degreeV; ++j) {
      Eigen::Vector4d v = Eigen::Vector4d::Zero();
      for (int a = 0; a + i <= p.degreeU; ++a)
        for (int b = 0; b + j <= p.degreeV; ++b)
          v += bernstein(p.degreeU - i, a, s) * bernstein(p.degreeV - j, b, t) * differenceCoefficient(p, i, j, a, b);
      for (int q = 0; q < 4; ++q) H[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)][static_cast<std::size_t>(q)] = {v[q], v[q]};
    }
  return H;
}

/// S_(i,j) from X = W·S by Leibniz: S_α = (X_α − Σ_{0<β<=α} C(α,β) W_β S_(α−β)) / W, from S itself. False for a
/// weight range that is not positive.
bool rationalDerivatives(const HomogeneousDerivatives& H, const IntervalVec3& point, Derivatives& S) {
  const Interval W = H[0][0][3];
  if (!(W.lo > 0)) return false;
  S[0][0] = point;
  for (int order = 1; order <= kOrder; ++order)
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
  if (!rationalDerivatives(homogeneousRanges(p), {Interval{lo[0], hi[0]}, {lo[1], hi[1]}, {lo[2], hi[2]}}, S)) return false;
  for (int i = 0; i <= kOrder; ++i)
    for (int j = 0; i + j <= kOrder; ++j)
      for (Interval& c : S[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)]) c = (1 / (std::pow(ws, i) * std::pow(wt, j))) * c;
  return true;
}

bool valuesAt(const RationalBezierPatch& p, double s, double t, Derivatives& S) {
  const HomogeneousDerivatives H = homogeneousValues(p, s, t);
  const double w = H[0][0][3].lo;
  IntervalVec3 point;
  for (std::size_t q = 0; q < 3; ++q) point[q] = {H[0][0][q].lo / w, H[0][0][q].lo / w};
  return rationalDerivatives(H, point, S);
}

RationalBezierPatch mapped(RationalBezierPatch p, const Eigen::Isometry3d& X) {
  for (Eigen::Vector4d& h : p.net) h.head<3>() = X.linear() * h.head<3>() + h[3] * X.translation();
  return p;
}

/// Derivatives of r = S_A(s,t) − S_B(u,v), by the variables they are taken in (0, 1: A's s, t; 2, 3: B's u, v):
/// mixed A–B derivatives vanish.
struct Residual {
  const Derivatives& A;
  const Derivatives& B;

  IntervalVec3 operator()(std::initializer_list<int> vars) const {
    int onA = 0, onB = 0, s = 0, t = 0;
    for (const int v : vars) {
      (v < 2 ? onA : onB) += 1;
      (v % 2 == 0 ? s : t) += 1;
    }
    if (onA > 0 && onB > 0) return {};
    if (onB == 0 && onA == 0) return A[0][0] - B[0][0];
    return onB == 0 ? A[static_cast<std::size_t>(s)][static_cast<std::size_t>(t)]
                    : -B[static_cast<std::size_t>(s)][static_cast<std::size_t>(t)];
  }
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
  Derivatives boxA, boxB, atA, atB;
  if (!encloseOver(subpatch(aC, lo[0], hi[0], lo[1], hi[1]), width[0], width[1], boxA) ||
      !encloseOver(subpatch(bC, lo[2], hi[2], lo[3], hi[3]), width[2], width[3], boxB) ||
      !valuesAt(aC, x[0], x[1], atA) || !valuesAt(bC, x[2], x[3], atB))
    return out;
  const Residual box{boxA, boxB}, at{atA, atB};

  // f, its gradient and Hessian at x: H_pq = r_p·r_q + r·r_pq.
  const Eigen::Vector3d r = mid(at({}));
  std::array<Eigen::Vector3d, 4> J;
  for (int p = 0; p < 4; ++p) J[static_cast<std::size_t>(p)] = mid(at({p}));
  Eigen::Matrix4d Hx;
  Eigen::Vector4d g;
  for (int p = 0; p < 4; ++p) {
    g[p] = r.dot(J[static_cast<std::size_t>(p)]);
    for (int q = 0; q < 4; ++q) Hx(p, q) = J[static_cast<std::size_t>(p)].dot(J[static_cast<std::size_t>(q)]) + r.dot(mid(at({p, q})));
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
        const std::array<std::array<std::initializer_list<int>, 2>, 4> terms = {{{{{p, c}, {q}}},
                                                                                 {{{p}, {q, c}}},
                                                                                 {{{c}, {p, q}}},
                                                                                 {{{}, {p, q, c}}}}};
        double value = 0, spread = 0;
        for (const auto& [u, v] : terms) {
          value += mid(at(u)).dot(mid(at(v)));
          spread += dotDeviation(box(u), at(u), box(v), at(v));
        }
        dH(p, q) = dH(q, p) = value;
        deviation(p, q) = deviation(q, p) = spread;
      }
    const double pointPart = (P * dH * P).cwiseAbs().rowwise().sum().maxCoeff();  // >= its spectral norm
    relative += reach[c] * (pointPart + spectralBound(P.cwiseAbs() * deviation * P.cwiseAbs()));
  }
  // Rounding of H(x), of its eigen-decomposition and of the sums above.
  relative += spectralBound(P.cwiseAbs() * Eigen::Matrix4d::Constant(1e-12 * Hx.cwiseAbs().maxCoeff()) * P.cwiseAbs());
  out.ratio = relative;
  if (!(out.ratio < 1)) return out;

  // Convex: f(y) >= f(x) + g·(y − x) on the box; g's rounding (each factor's coordinates to kRounding) widened.
  const double scale = centre.cwiseAbs().maxCoeff() + r.norm();
  double f = 0.5 * r.squaredNorm();
  for (int c = 0; c < 4; ++c) {
    const double slack = kRounding * scale * J[static_cast<std::size_t>(c)].norm();
    f += std::min(g[c] * (lo[c] - x[c]), g[c] * (hi[c] - x[c])) - slack * reach[c];
  }
  out.proved = true;
  out.lower = std::max(0.0, std::sqrt(2 * std::max(0.0, f)) - kRounding * scale);
  return out;
}

}  // namespace unidist::nurbs
