#include "nurbs/point_convexity.h"
#include "nurbs/bernstein_product.h"

#include <Eigen/Core>

#include <cmath>
#include <limits>
#include <memory>

namespace unidist::nurbs {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
// The subdivided net's rounding, as the balls allow for it (patch_tree.cpp, ballOfNet): 256 ulps.
constexpr double kNetUlps = 256;
// A point of a patch is evaluated to within a few ulps of its coordinates: the distance there to this many.
constexpr double kValueUlps = 32;
// Beyond this degree the forms (degree 4n) cost more than the searches they would save.
constexpr int kMaxFormDegree = 5;

double norm(double x) { return std::abs(x); }
double norm(const Eigen::Vector3d& x) { return x.norm(); }

/// A polynomial in Bernstein form of degree (du, dv) (coefficients u-major), with bounds on its coefficients'
/// size and on their distance from the exact polynomial's.
template <class T>
struct Grid {
  int du = 0, dv = 0;
  std::vector<T> c;
  double size = 0, err = 0;

  const T& at(int i, int j) const { return c[static_cast<std::size_t>(i * (dv + 1) + j)]; }
  void measure() {
    size = 0;
    for (const T& x : c) size = std::max(size, norm(x));
  }
};

/// The product (coefficients combined by mul; bernstein_product.h), its size and error bounds: Bernstein product
/// weights sum to one per coefficient, so sizes multiply; each coefficient sums at most (da + 1)(db + 1) rounded
/// products.
template <class T, class T1, class B, class Mul>
Grid<T> product(const Grid<T1>& a, const Grid<B>& b, Mul mul, const T& zero) {
  Grid<T> out;
  out.du = a.du + b.du;
  out.dv = a.dv + b.dv;
  nurbs::product(a.du, a.dv, a.c, b.du, b.dv, b.c, mul, zero, out.c);
  out.measure();
  const double terms = (a.du + 1.0) * (a.dv + 1.0) * (b.du + 1.0) * (b.dv + 1.0);
  out.err = a.size * b.err + a.err * b.size + a.err * b.err + 4 * terms * kEps * a.size * b.size;
  return out;
}

/// ∂/∂s (alongS) or ∂/∂t: the degree times forward differences.
template <class T>
Grid<T> derivative(const Grid<T>& g, bool alongS) {
  Grid<T> out;
  out.du = g.du - (alongS ? 1 : 0);
  out.dv = g.dv - (alongS ? 0 : 1);
  const double degree = alongS ? g.du : g.dv;
  for (int i = 0; i <= out.du; ++i)
    for (int j = 0; j <= out.dv; ++j)
      out.c.push_back(degree * (alongS ? g.at(i + 1, j) - g.at(i, j) : g.at(i, j + 1) - g.at(i, j)));
  out.measure();
  out.err = 2 * degree * (g.err + kEps * g.size);
  return out;
}

template <class T>
Grid<T> difference(const Grid<T>& a, const Grid<T>& b) {
  Grid<T> out = a;
  for (std::size_t k = 0; k < out.c.size(); ++k) out.c[k] = a.c[k] - b.c[k];
  out.measure();
  out.err = a.err + b.err + kEps * (a.size + b.size);
  return out;
}

template <class T>
Grid<T> sum(const Grid<T>& a, const Grid<T>& b) {
  Grid<T> out = a;
  for (std::size_t k = 0; k < out.c.size(); ++k) out.c[k] = a.c[k] + b.c[k];
  out.measure();
  out.err = a.err + b.err + kEps * (a.size + b.size);
  return out;
}

/// The polynomial's value at the middle of its box (de Casteljau, halving: rounding within its size's ulps).
template <class T>
T middle(const Grid<T>& g) {
  std::vector<T> c = g.c;
  for (int i = 0; i <= g.du; ++i)  // each row along t
    for (int level = g.dv; level > 0; --level)
      for (int j = 0; j < level; ++j) {
        T& x = c[static_cast<std::size_t>(i * (g.dv + 1) + j)];
        x = 0.5 * (x + c[static_cast<std::size_t>(i * (g.dv + 1) + j + 1)]);
      }
  for (int level = g.du; level > 0; --level)  // then the first column along s
    for (int i = 0; i < level; ++i) {
      T& x = c[static_cast<std::size_t>(i * (g.dv + 1))];
      x = 0.5 * (x + c[static_cast<std::size_t>((i + 1) * (g.dv + 1))]);
    }
  return c.front();
}

std::shared_ptr<const CurvatureForm> makeForm(const PatchNode& n) {
  auto F = std::make_shared<CurvatureForm>();
  const RationalBezierPatch& net = n.net;
  const int p = net.degreeU, q = net.degreeV;
  if (std::max(p, q) > kMaxFormDegree) return F;
  F->centre = n.ball.center;
  double scale = F->centre.cwiseAbs().maxCoeff(), wmax = 0;
  for (const Eigen::Vector3d& x : n.points) scale = std::max(scale, x.cwiseAbs().maxCoeff() + F->centre.cwiseAbs().maxCoeff());
  Grid<Eigen::Vector3d> X{p, q, {}, 0, 0};  // X' = X − c W
  Grid<double> W{p, q, {}, 0, 0};
  for (const Eigen::Vector4d& h : net.net) {
    X.c.push_back(h.head<3>() - F->centre * h[3]);
    W.c.push_back(h[3]);
    wmax = std::max(wmax, h[3]);
  }
  X.measure();
  W.measure();
  // The net's points may be off the exact subpatch's by 256 ulps of the coordinates and its weights by 256 ulps.
  X.err = 2 * kNetUlps * kEps * scale * wmax * std::sqrt(3.0);
  W.err = kNetUlps * kEps * wmax;
  // D_s and D_t from the Euclidean points (derivativeCoefficients: equal points give exactly zero), over the
  // degree: each term w_c (w_a (P_a − P_c) − w_b (P_b − P_c)) is off by 4 point errors and 2 weight errors.
  Grid<Eigen::Vector3d> D[2];
  const double errD = 8 * kNetUlps * kEps * scale * wmax * wmax * std::sqrt(3.0);
  for (int a = 0; a < 2; ++a) {
    const std::vector<Eigen::Vector3d> coefficients = derivativeCoefficients(net, a == 1);
    const int degree = a == 0 ? p : q;
    Grid<Eigen::Vector3d>& d = D[a];
    d.du = a == 0 ? 2 * p - 1 : 2 * p;
    d.dv = a == 0 ? 2 * q : 2 * q - 1;
    d.c.resize(coefficients.size());
    // Sv's come v-major (degree (2q − 1, 2p)): transposed to u-major.
    for (int i = 0; i <= d.du; ++i)
      for (int j = 0; j <= d.dv; ++j)
        d.c[static_cast<std::size_t>(i * (d.dv + 1) + j)] =
            degree * coefficients[static_cast<std::size_t>(a == 0 ? i * (d.dv + 1) + j : j * (d.du + 1) + i)];
    d.measure();
    d.err = degree * errD + 16.0 * (p + 1) * (q + 1) * kEps * d.size;
  }
  const Grid<double> Wd[2] = {derivative(W, true), derivative(W, false)};
  const int pairs[3][2] = {{0, 0}, {0, 1}, {1, 1}};
  bool finite = true;
  for (std::size_t k = 0; k < 3; ++k) {
    const int a = pairs[k][0], b = pairs[k][1];
    // E_ab = (D_a)_b W − 2 W_b D_a.
    const Grid<Eigen::Vector3d> first = product(W, derivative(D[a], b == 0), scaledBy, Eigen::Vector3d::Zero().eval());
    Grid<Eigen::Vector3d> second = product(Wd[b], D[a], scaledBy, Eigen::Vector3d::Zero().eval());
    for (Eigen::Vector3d& x : second.c) x *= 2;
    second.size *= 2;
    second.err *= 2;
    const Grid<Eigen::Vector3d> E = difference(first, second);
    const Grid<double> P = sum(product(D[a], D[b], dotOf, 0.0), product(X, E, dotOf, 0.0));
    const Grid<Eigen::Vector3d> Q = product(W, E, scaledBy, Eigen::Vector3d::Zero().eval());
    F->middleP[k] = middle(P);
    F->middleQ[k] = middle(Q);
    for (const double x : P.c) F->spreadP[k] = std::max(F->spreadP[k], std::abs(x - F->middleP[k]));
    for (const Eigen::Vector3d& x : Q.c) F->spreadQ[k] = std::max(F->spreadQ[k], (x - F->middleQ[k]).norm());
    F->p[k] = P.c;
    for (int c = 0; c < 3; ++c)
      for (const Eigen::Vector3d& x : Q.c) F->q[k][static_cast<std::size_t>(c)].push_back(x[c]);
    F->sizeP[k] = P.size;
    F->sizeQ[k] = Q.size;
    F->errP[k] = P.err;
    F->errQ[k] = Q.err;
    finite = finite && std::isfinite(P.size + Q.size + P.err + Q.err);
  }
  F->weight4 = std::pow(wmax, 4) * (1 + 1e-12);
  F->valid = finite;
  return F;
}

std::size_t formBytes(const CurvatureForm& F) {
  std::size_t doubles = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    doubles += F.p[k].capacity();
    for (const std::vector<double>& x : F.q[k]) doubles += x.capacity();
  }
  return sizeof(CurvatureForm) + doubles * sizeof(double);
}

}  // namespace

bool convexAtMiddle(const PatchNode& n, const Eigen::Vector3d& q) {
  const SurfaceDerivatives d = n.net.derivatives(0.5, 0.5);
  const Eigen::Vector3d r = d.point - q;
  const double a = d.du.dot(d.du) + r.dot(d.duu), b = d.du.dot(d.dv) + r.dot(d.duv), c = d.dv.dot(d.dv) + r.dot(d.dvv);
  return a > 0 && c > 0 && a * c > b * b;
}

const CurvatureForm& curvatureForm(const PatchNode& n, const PatchForest& forest) {
  std::call_once(n.curvatureOnce, [&n, &forest] {
    n.curvature = makeForm(n);
    if (n.kept) forest.bytes += formBytes(*n.curvature);  // deeper nodes die with their query
  });
  return *n.curvature;
}

namespace {

/// How far a coefficient P − r·Q of entry k may be from the exact one: the form's errors, r's rounding (an ulp of
/// the larger of q and the centre in each coordinate), and, with `reach`, every point within that distance of q
/// (it moves each coefficient by at most reach |Q|).
double coefficientMargin(const CurvatureForm& F, std::size_t k, const Eigen::Vector3d& q, double reach) {
  const double dr = 2 * kEps * (q.cwiseAbs().maxCoeff() + F.centre.cwiseAbs().maxCoeff()) * std::sqrt(3.0);
  const double rn = (q - F.centre).norm();
  return F.errP[k] + (rn + reach) * F.errQ[k] + (dr + reach) * F.sizeQ[k] * (1 + 1e-12) +
         8 * kEps * (F.sizeP[k] + (rn + reach) * F.sizeQ[k]);
}

}  // namespace

double leastCurvature(const CurvatureForm& F, const Eigen::Vector3d& q, double reach) {
  if (!F.valid) return 0;
  const Eigen::Vector3d r = q - F.centre;
  const double rn = r.norm();
  const auto margin = [&](std::size_t k) { return coefficientMargin(F, k, q, reach); };
  double lo[3], hi[3];
  // First the node's middle and the coefficients' spread about it: a few flops, and where the middle is not
  // positive definite the function is not convex there at all.
  for (std::size_t k = 0; k < 3; ++k) {
    const double middle = F.middleP[k] - r.dot(F.middleQ[k]);
    const double spread = F.spreadP[k] + (rn + reach) * F.spreadQ[k] + 2 * margin(k);
    lo[k] = middle - spread;
    hi[k] = middle + spread;
    // The coefficients' least value is at most the middle's (rounding aside): a diagonal entry that is not
    // clearly positive there cannot be proved positive (at a centre of curvature it vanishes).
    if (k != 1 && !(middle > margin(k) + 1e-9 * F.sizeP[k])) return 0;
  }
  if (!(lo[0] > 0 && lo[2] > 0 && lo[0] * lo[2] > (1 + 1e-12) * std::max(-lo[1], hi[1]) * std::max(-lo[1], hi[1]))) {
    // Then every coefficient: the least of the diagonal entries (which stop the test when not positive), the
    // largest magnitude of the other.
    const double rx = r.x(), ry = r.y(), rz = r.z();
    const auto range = [&](std::size_t k, double& low, double& high) {
      const double* P = F.p[k].data();
      const double *X = F.q[k][0].data(), *Y = F.q[k][1].data(), *Z = F.q[k][2].data();
      double least = std::numeric_limits<double>::infinity(), most = -least;
      for (std::size_t i = 0; i < F.p[k].size(); ++i) {
        const double c = P[i] - rx * X[i] - ry * Y[i] - rz * Z[i];
        least = std::min(least, c);
        most = std::max(most, c);
      }
      low = least - margin(k);
      high = most + margin(k);
    };
    range(0, lo[0], hi[0]);
    if (!(lo[0] > 0)) return 0;
    range(2, lo[2], hi[2]);
    if (!(lo[2] > 0)) return 0;
    range(1, lo[1], hi[1]);
  }
  // Every symmetric [a b; b d] with a >= a0, d >= d0, |b| <= b0 has least eigenvalue at least that of
  // [a0 b0; b0 d0] (adding a non-negative diagonal raises it; the sign of b does not change it). W⁴ H is
  // such a matrix at every point, and W⁴ <= weight4.
  const double a0 = lo[0], d0 = lo[2], b0 = std::max(-lo[1], hi[1]);
  if (!(a0 > 0 && d0 > 0 && a0 * d0 > (1 + 1e-12) * b0 * b0)) return 0;
  const double least = 0.5 * ((a0 + d0) - std::sqrt((a0 - d0) * (a0 - d0) + 4 * b0 * b0));
  return std::max(0.0, least * (1 - 1e-9) / F.weight4);
}

namespace {

/// f(h) raised or lowered by the least of g (y − h) + ½ curvature (y − h)² over the node's range of one parameter
/// (c: 0 for s, 1 for t), with the gradient component known to within h.gradientError (see convexDistanceBound).
double convexTerm(const PatchNode& n, const PatchHit& h, int c, double curvature) {
  const double lo = c == 0 ? n.s0 : n.t0, hi = c == 0 ? n.s1 : n.t1, at = c == 0 ? h.s : h.t;
  const double g = h.gradient[c], e = h.gradientError, width = hi - lo;
  const double reach = std::max(at - lo, hi - at);
  const bool outward = (at <= lo && g >= 0) || (at >= hi && g <= 0);
  if (outward) return -std::max(0.0, e - std::abs(g)) * reach;
  const double plane = std::min(g * (lo - at), g * (hi - at)) - e * reach;
  const double gw = (std::abs(g) + e) * width;
  return curvature > 0 ? std::max(plane, -gw * gw / (2 * curvature)) : plane;
}

/// The distance whose half square is at least f, less the rounding of the point's evaluation.
double distanceOf(double f, const Eigen::Vector3d& q, const PatchHit& h) {
  const double scale = q.cwiseAbs().maxCoeff() + h.point.cwiseAbs().maxCoeff() + h.value;
  return std::sqrt(2 * std::max(0.0, f)) - kValueUlps * kEps * scale;
}

/// A proved lower bound on the second derivative of ½|S − q|² along a patch edge the node touches (alongT: the
/// edge s = const, `last` its s = 1 side; else the edge t = const), over the node's own parameters: the least
/// coefficient of that entry's line of the form, over the largest W⁴. Zero where not positive.
double leastAlongEdge(const CurvatureForm& F, const PatchNode& n, const Eigen::Vector3d& q, bool alongT, bool last) {
  if (!F.valid) return 0;
  const int p = n.net.degreeU, qd = n.net.degreeV;
  // Degrees of the ss and tt entries: (4p − 2, 4q) and (4p, 4q − 2), u-major.
  const std::size_t k = alongT ? 2 : 0;
  const int rows = alongT ? 4 * p + 1 : 4 * p - 1, cols = alongT ? 4 * qd - 1 : 4 * qd + 1;
  const Eigen::Vector3d r = q - F.centre;
  const double *P = F.p[k].data(), *X = F.q[k][0].data(), *Y = F.q[k][1].data(), *Z = F.q[k][2].data();
  double least = std::numeric_limits<double>::infinity();
  const int count = alongT ? cols : rows;
  for (int m = 0; m < count; ++m) {
    const int i = alongT ? (last ? rows - 1 : 0) : m, j = alongT ? m : (last ? cols - 1 : 0);
    const std::size_t at = static_cast<std::size_t>(i * cols + j);
    least = std::min(least, P[at] - r.x() * X[at] - r.y() * Y[at] - r.z() * Z[at]);
  }
  least -= coefficientMargin(F, k, q, 0);
  return least > 0 ? least * (1 - 1e-9) / F.weight4 : 0;
}

}  // namespace

double edgeDistanceBound(const PatchNode& n, const PatchForest& forest, const Eigen::Vector3d& q, const PatchHit& h,
                         GradientScratch& g) {
  const double none = -std::numeric_limits<double>::infinity();
  if (!std::isfinite(h.gradientError) || h.patch != n.patch) return none;
  // The patch edges through h that the node touches; +1 where the objective must increase with the parameter
  // (h on its 0 side), −1 where it must decrease.
  const int outS = (h.s == 0 && n.s0 == 0) ? 1 : (h.s == 1 && n.s1 == 1) ? -1 : 0;
  const int outT = (h.t == 0 && n.t0 == 0) ? 1 : (h.t == 1 && n.t1 == 1) ? -1 : 0;
  if (outS == 0 && outT == 0) return none;
  if (!(h.s >= n.s0 && h.s <= n.s1 && h.t >= n.t0 && h.t <= n.t1)) return none;
  const PointGradientSigns signs = pointGradientSigns(n, forest, q, g);
  // The component across an edge keeps its outward sign over the node: every point of it is farther than the
  // point of the edge it moves to along that parameter.
  const bool acrossS = outS != 0 && signs.whole[0] == outS, acrossT = outT != 0 && signs.whole[1] == outT;
  if (!acrossS && !acrossT) return none;
  // At a corner, the other component keeps its outward sign along that edge: the corner h is the nearest.
  const double f = 0.5 * h.value * h.value;
  if ((acrossS && outT != 0 && signs.along[outS > 0 ? 0 : 1] == outT) ||
      (acrossT && outS != 0 && signs.along[outT > 0 ? 2 : 3] == outS))
    return distanceOf(f, q, h);
  // Along the edge: convex there, so above its tangent at h, or its parabola's least value.
  const bool alongT = acrossS;
  const double curvature = leastAlongEdge(curvatureForm(n, forest), n, q, alongT, alongT ? outS < 0 : outT < 0);
  if (!(curvature > 0)) return none;
  return distanceOf(f + convexTerm(n, h, alongT ? 1 : 0, curvature), q, h);
}

double convexDistanceBound(const PatchNode& n, const Eigen::Vector3d& q, const PatchHit& h, double curvature) {
  if (!std::isfinite(h.gradientError) || !(curvature > 0)) return -std::numeric_limits<double>::infinity();
  // Convex on the box: f(y) >= f(h) + g·(y − h) + ½ curvature |y − h|² (y in the node's own parameters, where
  // the gradient is g times the box's widths). Per component: at a face of the box the gradient points out of
  // (the run stopped there), the term is not negative once |g| exceeds its error, else at least −(error − |g|)·
  // reach; otherwise the plane's least value at a face, or the parabola's least value −(g w)² / (2 curvature),
  // whichever is higher. g is known to within gradientError.
  const double f = 0.5 * h.value * h.value + convexTerm(n, h, 0, curvature) + convexTerm(n, h, 1, curvature);
  return distanceOf(f, q, h);
}

}  // namespace unidist::nurbs
