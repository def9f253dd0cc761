// NurbsSurface: validation, exact evaluation (homogeneous sum + rational quotient rule), Bézier extraction.
#include "unidist/nurbs.h"

#include "nurbs/bspline.h"
#include "nurbs/reparametrise.h"

#include <array>
#include <cmath>
#include <string>

namespace unidist {
namespace {

std::string str(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

void checkKnots(const std::vector<double>& knots, int degree, int count, const char* name) {
  const std::size_t expected = static_cast<std::size_t>(count + degree + 1);
  if (knots.size() != expected)
    throw InputError(std::string(name) + ": wrong length " + std::to_string(knots.size()) + " (expected " +
                     std::to_string(expected) + " = control points " + std::to_string(count) + " + degree " +
                     std::to_string(degree) + " + 1)");
  for (std::size_t i = 0; i < knots.size(); ++i) {
    if (!std::isfinite(knots[i])) throw InputError(std::string(name) + "[" + std::to_string(i) + "] is not finite");
    if (i > 0 && knots[i] < knots[i - 1])
      throw InputError(std::string(name) + " is decreasing at index " + std::to_string(i) + " (" + str(knots[i - 1]) +
                       " then " + str(knots[i]) + ")");
  }
  if (!(knots[static_cast<std::size_t>(count)] > knots[static_cast<std::size_t>(degree)]))
    throw InputError(std::string(name) + ": zero-length parameter domain [" + str(knots[static_cast<std::size_t>(degree)]) +
                     ", " + str(knots[static_cast<std::size_t>(count)]) + "]");
}

/// The rational quotient rule: S = A/w and its derivatives from the homogeneous A = (w S, w) and its derivatives.
SurfaceDerivatives quotient(const Eigen::Vector4d& A, const Eigen::Vector4d& Au, const Eigen::Vector4d& Av,
                            const Eigen::Vector4d& Auu, const Eigen::Vector4d& Auv, const Eigen::Vector4d& Avv) {
  SurfaceDerivatives d;
  const double w = A[3];
  d.point = A.head<3>() / w;
  d.du = (Au.head<3>() - Au[3] * d.point) / w;
  d.dv = (Av.head<3>() - Av[3] * d.point) / w;
  d.duu = (Auu.head<3>() - 2 * Au[3] * d.du - Auu[3] * d.point) / w;
  d.dvv = (Avv.head<3>() - 2 * Av[3] * d.dv - Avv[3] * d.point) / w;
  d.duv = (Auv.head<3>() - Au[3] * d.dv - Av[3] * d.du - Auv[3] * d.point) / w;
  return d;
}

/// The net's sum Σ_ij B_i(s) B_j(t) P_ij with its first and second partial derivatives, from the bases' values
/// and derivatives (bu[k][i], bv[k][j]), then the rational quotient. Inline, so constant degrees unroll.
template <class Rows>
inline SurfaceDerivatives combine(const std::vector<Eigen::Vector4d>& net, int degreeU, int degreeV, const Rows& bu,
                                  const Rows& bv) {
  Eigen::Vector4d A = Eigen::Vector4d::Zero(), Au = A, Av = A, Auu = A, Auv = A, Avv = A;
  for (int i = 0; i <= degreeU; ++i) {
    Eigen::Vector4d row0 = Eigen::Vector4d::Zero(), row1 = row0, row2 = row0;  // sums over j of B_j^(k)(t) P_ij
    for (int j = 0; j <= degreeV; ++j) {
      const Eigen::Vector4d& P = net[static_cast<std::size_t>(i * (degreeV + 1) + j)];
      const auto uj = static_cast<std::size_t>(j);
      row0 += bv[0][uj] * P;
      row1 += bv[1][uj] * P;
      row2 += bv[2][uj] * P;
    }
    const auto ui = static_cast<std::size_t>(i);
    A += bu[0][ui] * row0;
    Av += bu[0][ui] * row1;
    Avv += bu[0][ui] * row2;
    Au += bu[1][ui] * row0;
    Auv += bu[1][ui] * row1;
    Auu += bu[2][ui] * row0;
  }
  return quotient(A, Au, Av, Auu, Auv, Avv);
}

/// RationalBezierPatch::derivatives for degrees (P, Q) known at compile time (the Newton polish evaluates
/// patches of degree <= 3 in nearly every query; the general loops cost it about twice as much). The same
/// operations in the same order as the general case, so the same bits.
template <int P, int Q>
SurfaceDerivatives derivativesOfDegree(const std::vector<Eigen::Vector4d>& net, double s, double t) {
  constexpr int kRow = (P > Q ? P : Q) + 1;
  std::array<std::array<double, kRow>, 3> bu, bv;
  nurbs::bernstein(P, s, bu);
  nurbs::bernstein(Q, t, bv);
  return combine(net, P, Q, bu, bv);
}

}  // namespace

NurbsSurface::NurbsSurface(int degreeU, int degreeV, std::vector<double> knotsU, std::vector<double> knotsV,
                           std::vector<std::vector<Eigen::Vector4d>> controlPoints)
    : p_(degreeU), q_(degreeV), knotsU_(std::move(knotsU)), knotsV_(std::move(knotsV)) {
  for (int d : {p_, q_})
    if (d < 1 || d > kMaxNurbsDegree)
      throw InputError("degree " + std::to_string(d) + " out of range (1.." + std::to_string(kMaxNurbsDegree) + ")");
  nu_ = static_cast<int>(controlPoints.size());
  if (nu_ < p_ + 1)
    throw InputError("control net has " + std::to_string(nu_) + " rows in u; degree " + std::to_string(p_) +
                     " needs at least " + std::to_string(p_ + 1));
  nv_ = static_cast<int>(controlPoints[0].size());
  for (int i = 0; i < nu_; ++i)
    if (static_cast<int>(controlPoints[static_cast<std::size_t>(i)].size()) != nv_)
      throw InputError("control net row " + std::to_string(i) + " has " +
                       std::to_string(controlPoints[static_cast<std::size_t>(i)].size()) + " points, row 0 has " +
                       std::to_string(nv_));
  if (nv_ < q_ + 1)
    throw InputError("control net has " + std::to_string(nv_) + " columns in v; degree " + std::to_string(q_) +
                     " needs at least " + std::to_string(q_ + 1));
  checkKnots(knotsU_, p_, nu_, "knots_u");
  checkKnots(knotsV_, q_, nv_, "knots_v");
  homogeneous_.reserve(static_cast<std::size_t>(nu_ * nv_));
  for (int i = 0; i < nu_; ++i)
    for (int j = 0; j < nv_; ++j) {
      const Eigen::Vector4d& c = controlPoints[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
      const std::string where = "control point [" + std::to_string(i) + "][" + std::to_string(j) + "]";
      if (!c.head<3>().allFinite()) throw InputError(where + ": coordinate is not finite");
      if (!std::isfinite(c[3]) || !(c[3] > 0)) throw InputError(where + ": weight " + str(c[3]) + " is not positive");
      homogeneous_.emplace_back(c[0] * c[3], c[1] * c[3], c[2] * c[3], c[3]);
    }
}

Eigen::Vector4d NurbsSurface::controlPoint(int i, int j) const {
  const Eigen::Vector4d& h = homogeneous_[static_cast<std::size_t>(i * nv_ + j)];
  return {h[0] / h[3], h[1] / h[3], h[2] / h[3], h[3]};
}

SurfaceDerivatives NurbsSurface::derivatives(double u, double v) const {
  u = std::min(std::max(u, uMin()), uMax());
  v = std::min(std::max(v, vMin()), vMax());
  const nurbs::BasisRow bu = nurbs::basisWithDerivatives(knotsU_, p_, nurbs::findSpan(knotsU_, p_, nu_, u), u);
  const nurbs::BasisRow bv = nurbs::basisWithDerivatives(knotsV_, q_, nurbs::findSpan(knotsV_, q_, nv_, v), v);
  Eigen::Vector4d A = Eigen::Vector4d::Zero(), Au = A, Av = A, Auu = A, Auv = A, Avv = A;
  for (int a = 0; a <= p_; ++a)
    for (int b = 0; b <= q_; ++b) {
      const Eigen::Vector4d& P =
          homogeneous_[static_cast<std::size_t>((bu.span - p_ + a) * nv_ + (bv.span - q_ + b))];
      const auto ua = static_cast<std::size_t>(a), vb = static_cast<std::size_t>(b);
      A += bu.d[0][ua] * bv.d[0][vb] * P;
      Au += bu.d[1][ua] * bv.d[0][vb] * P;
      Av += bu.d[0][ua] * bv.d[1][vb] * P;
      Auu += bu.d[2][ua] * bv.d[0][vb] * P;
      Auv += bu.d[1][ua] * bv.d[1][vb] * P;
      Avv += bu.d[0][ua] * bv.d[2][vb] * P;
    }
  return quotient(A, Au, Av, Auu, Auv, Avv);
}

std::vector<RationalBezierPatch> NurbsSurface::bezierPatches() const {
  // Cut along u for every v column, then along v for every u row of each u segment.
  std::vector<nurbs::BezierSegments> columns;
  for (int j = 0; j < nv_; ++j) {
    std::vector<Eigen::Vector4d> column;
    for (int i = 0; i < nu_; ++i) column.push_back(homogeneous_[static_cast<std::size_t>(i * nv_ + j)]);
    columns.push_back(nurbs::toBezierSegments(knotsU_, p_, std::move(column)));
  }
  const nurbs::BezierSegments& first = columns.front();
  std::vector<RationalBezierPatch> out;
  for (std::size_t su = 0; su < first.segments.size(); ++su) {
    std::vector<nurbs::BezierSegments> rows;
    for (int i = 0; i <= p_; ++i) {
      std::vector<Eigen::Vector4d> row;
      for (int j = 0; j < nv_; ++j) row.push_back(columns[static_cast<std::size_t>(j)].segments[su][static_cast<std::size_t>(i)]);
      rows.push_back(nurbs::toBezierSegments(knotsV_, q_, std::move(row)));
    }
    for (std::size_t sv = 0; sv < rows.front().segments.size(); ++sv) {
      RationalBezierPatch patch;
      patch.degreeU = p_;
      patch.degreeV = q_;
      patch.u0 = first.breaks[su];
      patch.u1 = first.breaks[su + 1];
      patch.v0 = rows.front().breaks[sv];
      patch.v1 = rows.front().breaks[sv + 1];
      for (int i = 0; i <= p_; ++i)
        for (int j = 0; j <= q_; ++j) patch.net.push_back(rows[static_cast<std::size_t>(i)].segments[sv][static_cast<std::size_t>(j)]);
      nurbs::balanceWeights(patch);
      out.push_back(std::move(patch));
    }
  }
  return out;
}

NurbsSurface NurbsSurface::restricted(double u0, double u1, double v0, double v1) const {
  const auto check = [](double a, double b, double lo, double hi, const char* name) {
    if (!(std::isfinite(a) && std::isfinite(b) && a < b && a >= lo && b <= hi))
      throw InputError(std::string("NURBS surface: the ") + name + " range [" + std::to_string(a) + ", " +
                       std::to_string(b) + "] is empty or leaves the knot domain [" + std::to_string(lo) + ", " +
                       std::to_string(hi) + "]");
  };
  check(u0, u1, uMin(), uMax(), "u");
  check(v0, v1, vMin(), vMax(), "v");
  // Along u for every v column, then along v for every row of the result.
  std::vector<double> knotsU;
  std::vector<std::vector<Eigen::Vector4d>> columns;
  for (int j = 0; j < nv_; ++j) {
    std::vector<double> knots = knotsU_;
    std::vector<Eigen::Vector4d> column;
    for (int i = 0; i < nu_; ++i) column.push_back(homogeneous_[static_cast<std::size_t>(i * nv_ + j)]);
    nurbs::restrictCurve(knots, p_, column, u0, u1);
    knotsU = std::move(knots);
    columns.push_back(std::move(column));
  }
  std::vector<double> knotsV;
  std::vector<std::vector<Eigen::Vector4d>> net;
  for (std::size_t i = 0; i < columns.front().size(); ++i) {
    std::vector<double> knots = knotsV_;
    std::vector<Eigen::Vector4d> row;
    for (const auto& column : columns) row.push_back(column[i]);
    nurbs::restrictCurve(knots, q_, row, v0, v1);
    knotsV = std::move(knots);
    for (Eigen::Vector4d& h : row) h.head<3>() /= h[3];  // the constructor takes Euclidean points
    net.push_back(std::move(row));
  }
  return NurbsSurface(p_, q_, std::move(knotsU), std::move(knotsV), std::move(net));
}

Eigen::Vector2d RationalBezierPatch::surfaceParam(double s, double t) const {
  return {u0 + (u1 - u0) * nurbs::mobius(stretchU, s), v0 + (v1 - v0) * nurbs::mobius(stretchV, t)};
}

SurfaceDerivatives RationalBezierPatch::derivatives(double s, double t) const {
  switch (degreeU <= 3 && degreeV <= 3 ? degreeU * 4 + degreeV : 0) {
    case 1 * 4 + 1: return derivativesOfDegree<1, 1>(net, s, t);
    case 1 * 4 + 2: return derivativesOfDegree<1, 2>(net, s, t);
    case 1 * 4 + 3: return derivativesOfDegree<1, 3>(net, s, t);
    case 2 * 4 + 1: return derivativesOfDegree<2, 1>(net, s, t);
    case 2 * 4 + 2: return derivativesOfDegree<2, 2>(net, s, t);
    case 2 * 4 + 3: return derivativesOfDegree<2, 3>(net, s, t);
    case 3 * 4 + 1: return derivativesOfDegree<3, 1>(net, s, t);
    case 3 * 4 + 2: return derivativesOfDegree<3, 2>(net, s, t);
    case 3 * 4 + 3: return derivativesOfDegree<3, 3>(net, s, t);
    default: break;
  }
  std::array<std::array<double, kMaxNurbsDegree + 1>, 3> bu, bv;
  nurbs::bernstein(degreeU, s, bu);
  nurbs::bernstein(degreeV, t, bv);
  return combine(net, degreeU, degreeV, bu, bv);
}

Eigen::Vector3d RationalBezierPatch::evaluate(double s, double t) const { return derivatives(s, t).point; }

}  // namespace unidist
