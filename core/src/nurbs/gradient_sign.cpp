#include "nurbs/gradient_sign.h"
#include "nurbs/bernstein_product.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace unidist::nurbs {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
// The subdivided net's rounding, as the balls allow for it (patch_tree.cpp, ballOfNet): 256 ulps.
constexpr double kNetUlps = 256;

/// +1 or −1 when every value over rows k0..k1 and columns l0..l1 of a grid with `cols` columns is beyond
/// `margin` with that sign, else 0.
int signOver(const std::vector<double>& g, int cols, int k0, int k1, int l0, int l1, double margin) {
  int sign = 0;
  for (int k = k0; k <= k1; ++k)
    for (int l = l0; l <= l1; ++l) {
      const double x = g[static_cast<std::size_t>(k * cols + l)];
      const int here = x > margin ? 1 : (x < -margin ? -1 : 0);
      if (here == 0 || (sign != 0 && here != sign)) return 0;
      sign = here;
    }
  return sign;
}

/// The largest distance of the points of the node's net row (an s edge) or column (a t edge) `line` from its
/// first point.
double edgeSpread(const PatchNode& n, bool sEdge, int line) {
  const int count = sEdge ? n.net.degreeV : n.net.degreeU;
  const Eigen::Vector3d first = sEdge ? n.net.point(line, 0) : n.net.point(0, line);
  double spread = 0;
  for (int k = 1; k <= count; ++k)
    spread = std::max(spread, ((sEdge ? n.net.point(line, k) : n.net.point(k, line)) - first).norm());
  return spread;
}

/// The sign of a numerator (grid of degree (a, b), `cols` = b + 1) over the node away from its collapsed edges
/// (pole[0..3]: s = 0, s = 1, t = 0, t = 1): +1 or −1 when every coefficient off those edges' lines has it
/// beyond `margin`. A line on a collapsed edge may fall short by κ (there the gradient vanishes with the
/// edge's speed, up to rounding): with m the least other magnitude, N = Σ c_l(s) B_l(t) >= −κ (1−t)^b +
/// m (1 − (1−t)^b) > 0 once t > κ / (m + κ), so only a strip that close to the edge is left unproved, which must
/// lie within `negligible` of it (its speed times the strip's width).
int signAwayFromPoles(const std::vector<double>& g, int a, int b, const bool pole[4], double margin, double speedS,
                      double speedT, double negligible) {
  const int cols = b + 1;
  const auto onLine = [&](int k, int l) {
    return (pole[0] && k == 0) || (pole[1] && k == a) || (pole[2] && l == 0) || (pole[3] && l == b);
  };
  int sign = 0;
  double least = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= a; ++k)
    for (int l = 0; l <= b; ++l) {
      if (onLine(k, l)) continue;
      const double x = g[static_cast<std::size_t>(k * cols + l)];
      const int here = x > margin ? 1 : (x < -margin ? -1 : 0);
      if (here == 0 || (sign != 0 && here != sign)) return 0;
      sign = here;
      least = std::min(least, std::abs(x) - margin);
    }
  if (sign == 0) return 0;
  int short_ = -1;  // the one line allowed to fall short
  double kappa = 0;
  for (int k = 0; k <= a; ++k)
    for (int l = 0; l <= b; ++l) {
      if (!onLine(k, l)) continue;
      const double deficit = margin - sign * g[static_cast<std::size_t>(k * cols + l)];
      if (deficit <= 0) continue;
      const int line = (pole[0] && k == 0) ? 0 : (pole[1] && k == a) ? 1 : (pole[2] && l == 0) ? 2 : 3;
      if (short_ >= 0 && short_ != line) return 0;
      short_ = line;
      kappa = std::max(kappa, deficit);
    }
  if (short_ < 0) return sign;
  const double strip = kappa / (least + kappa) * (short_ < 2 ? speedS : speedT);
  return strip <= negligible ? sign : 0;
}

/// The numerators' coefficients u (∂/∂s) and v (∂/∂t), each known to within `margin`, prove the node free of
/// local minima over its patch: none inside (one component never zero), none on a patch edge it touches (the
/// component along the edge never zero, or the other pointing out of the patch), collapsed edges aside (a
/// pole: every point there is within `negligible` of the corner the search evaluates). Without the strip rule
/// every piece at a pole would fail (S_s vanishes along it) and be split down to the tolerance.
/// `signs` are those of all of u and all of v (combine's; the common case, no pole, needs no other pass).
bool noMinimum(const GradientForm& F, const std::vector<double>& u, const std::vector<double>& v, const int signs[2],
               const PatchNode& n, double margin, double negligible) {
  const bool s0 = n.s0 == 0, s1 = n.s1 == 1, t0 = n.t0 == 0, t1 = n.t1 == 1;
  const bool pole[4] = {s0 && F.edgeSpread[0] <= negligible, s1 && F.edgeSpread[1] <= negligible,
                        t0 && F.edgeSpread[2] <= negligible, t1 && F.edgeSpread[3] <= negligible};
  if (pole[0] || pole[1] || pole[2] || pole[3]) {
    if (signAwayFromPoles(u, F.su, F.tu, pole, margin, F.speedS, F.speedT, negligible) == 0 &&
        signAwayFromPoles(v, F.sv, F.tv, pole, margin, F.speedS, F.speedT, negligible) == 0)
      return false;
  } else if (signs[0] == 0 && signs[1] == 0) {
    return false;
  }
  const int cu = F.tu + 1, cv = F.tv + 1;
  // Edge s = 0: a minimum there has ∂/∂t = 0 and ∂/∂s >= 0; edge s = 1: ∂/∂s <= 0. Likewise for t.
  if (s0 && !pole[0] && signOver(v, cv, 0, 0, 0, F.tv, margin) == 0 && signOver(u, cu, 0, 0, 0, F.tu, margin) >= 0)
    return false;
  if (s1 && !pole[1] && signOver(v, cv, F.sv, F.sv, 0, F.tv, margin) == 0 &&
      signOver(u, cu, F.su, F.su, 0, F.tu, margin) <= 0)
    return false;
  if (t0 && !pole[2] && signOver(u, cu, 0, F.su, 0, 0, margin) == 0 && signOver(v, cv, 0, F.sv, 0, 0, margin) >= 0)
    return false;
  if (t1 && !pole[3] && signOver(u, cu, 0, F.su, F.tu, F.tu, margin) == 0 &&
      signOver(v, cv, 0, F.sv, F.tv, F.tv, margin) <= 0)
    return false;
  return true;
}

std::shared_ptr<const GradientForm> makeForm(const PatchNode& n) {
  auto F = std::make_shared<GradientForm>();
  const RationalBezierPatch& net = n.net;
  const int p = net.degreeU, q = net.degreeV;
  F->centre = n.ball.center;
  // Largest coordinate, largest and smallest weight, and largest distance from the centre.
  double scale = 0, wmax = 0, wmin = std::numeric_limits<double>::infinity(), reach = 0;
  for (std::size_t k = 0; k < net.net.size(); ++k) {
    const Eigen::Vector4d& h = net.net[k];
    const Eigen::Vector3d& P = n.points[k];
    scale = std::max(scale, P.cwiseAbs().maxCoeff());
    wmax = std::max(wmax, h[3]);
    wmin = std::min(wmin, h[3]);
    reach = std::max(reach, (P - F->centre).norm());
  }
  std::vector<Eigen::Vector3d> du = derivativeCoefficients(net, false), dvT = derivativeCoefficients(net, true);
  // Sv's coefficients come v-major (degree (2q − 1, 2p)): transposed to u-major (2p, 2q − 1).
  std::vector<Eigen::Vector3d> dv(dvT.size());
  for (int j = 0; j < 2 * q; ++j)
    for (int i = 0; i <= 2 * p; ++i)
      dv[static_cast<std::size_t>(i * (2 * q) + j)] = dvT[static_cast<std::size_t>(j * (2 * p + 1) + i)];
  double dumax = 0, dvmax = 0;
  for (const auto& d : du) dumax = std::max(dumax, d.norm());
  for (const auto& d : dv) dvmax = std::max(dvmax, d.norm());
  const double dmax = std::max(dumax, dvmax);
  // |S_s| = p |D_s| / W² (the coefficients are the numerator's over p), bounded by the coefficients' hull.
  F->speedS = p * dumax / (wmin * wmin) * (1 + 1e-12);
  F->speedT = q * dvmax / (wmin * wmin) * (1 + 1e-12);
  std::vector<Eigen::Vector3d> X(net.net.size());  // X' = X − c W
  std::vector<double> W(net.net.size());
  for (std::size_t k = 0; k < net.net.size(); ++k) {
    X[k] = net.net[k].head<3>() - F->centre * net.net[k][3];
    W[k] = net.net[k][3];
  }
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  product(p, q, X, 2 * p - 1, 2 * q, du, dotOf, 0.0, F->pu);
  std::vector<Eigen::Vector3d> qu, qv;
  product(p, q, W, 2 * p - 1, 2 * q, du, scaledBy, zero, qu);
  product(p, q, X, 2 * p, 2 * q - 1, dv, dotOf, 0.0, F->pv);
  product(p, q, W, 2 * p, 2 * q - 1, dv, scaledBy, zero, qv);
  for (int c = 0; c < 3; ++c) {
    for (const Eigen::Vector3d& x : qu) F->qu[static_cast<std::size_t>(c)].push_back(x[c]);
    for (const Eigen::Vector3d& x : qv) F->qv[static_cast<std::size_t>(c)].push_back(x[c]);
  }
  F->su = 3 * p - 1;
  F->tu = 3 * q;
  F->sv = 3 * p;
  F->tv = 3 * q - 1;
  // Bernstein product weights sum to 1 per coefficient, so sizes multiply. The net's points may be off by
  // 256 ulps of the coordinates and its weights by 256 ulps: D (sums of w w (P − P)) by deltaD, X' by deltaX.
  const double deltaX = 2 * kNetUlps * kEps * (scale + F->centre.cwiseAbs().maxCoeff()) * std::sqrt(3.0) * wmax;
  // D's own sums (p (q + 1)² terms each) round within the same kind of allowance.
  const double ulpsD = kNetUlps + 4.0 * p * (q + 1) * (std::max(p, q) + 1);
  const double deltaD = 4 * ulpsD * kEps * scale * std::sqrt(3.0) * wmax * wmax + 3 * kNetUlps * kEps * dmax;
  const double rounding = (16.0 * (p + 1) * (q + 1) + 64) * kEps;  // the sums here, relative to the sizes
  F->sizeP = wmax * reach * dmax + deltaX * dmax;
  F->sizeQ = wmax * dmax;
  F->errP = wmax * reach * deltaD + deltaX * (dmax + deltaD) + rounding * F->sizeP;
  F->errQ = wmax * deltaD + kNetUlps * kEps * F->sizeQ + rounding * F->sizeQ;
  F->edgeSpread[0] = edgeSpread(n, true, 0);
  F->edgeSpread[1] = edgeSpread(n, true, p);
  F->edgeSpread[2] = edgeSpread(n, false, 0);
  F->edgeSpread[3] = edgeSpread(n, false, q);
  return F;
}

std::size_t formBytes(const GradientForm& F) {
  std::size_t doubles = F.pu.capacity() + F.pv.capacity();
  for (int c = 0; c < 3; ++c) doubles += F.qu[static_cast<std::size_t>(c)].capacity() + F.qv[static_cast<std::size_t>(c)].capacity();
  return sizeof(GradientForm) + doubles * sizeof(double);
}

}  // namespace

const Eigen::Vector3d* collapsedCorner(const PatchNode& n, const PatchForest& forest, double negligible) {
  // An edge whose net line lies within `negligible` of its first point is collapsed (a pole): every point of it
  // is within that of the corner the search evaluates. The spreads are the node's form's (made once).
  const double* spread = gradientForm(n, forest).edgeSpread;
  if (n.s0 == 0 && spread[0] <= negligible) return &n.corners[0];
  if (n.s1 == 1 && spread[1] <= negligible) return &n.corners[1];
  if (n.t0 == 0 && spread[2] <= negligible) return &n.corners[0];
  if (n.t1 == 1 && spread[3] <= negligible) return &n.corners[2];
  return nullptr;
}

const GradientForm& gradientForm(const PatchNode& n, const PatchForest& forest) {
  std::call_once(n.gradientOnce, [&n, &forest] {
    n.gradient = makeForm(n);
    if (n.kept) forest.bytes += formBytes(*n.gradient);  // deeper nodes die with their query
  });
  return *n.gradient;
}

/// The coefficients c_k = p_k − r·q_k into out (p empty: 0 − r·q_k); +1 or −1 when every one lies beyond
/// `margin` with that sign, else 0. Eigen's array expressions keep both passes vectorised; the callers check
/// that |p| + |r|·|q| stays finite (boundedSizes), so no coefficient is NaN.
int combine(const std::vector<double>& p, const Eigen::Vector3d& r, const std::array<std::vector<double>, 3>& q,
            double margin, std::vector<double>& out) {
  using Coefficients = Eigen::Map<const Eigen::ArrayXd>;
  const Eigen::Index count = static_cast<Eigen::Index>(q[0].size());
  out.resize(q[0].size());
  Eigen::Map<Eigen::ArrayXd> c(out.data(), count);
  const auto along = r.x() * Coefficients(q[0].data(), count) + r.y() * Coefficients(q[1].data(), count) +
                     r.z() * Coefficients(q[2].data(), count);
  if (p.empty()) {
    c = -along;
  } else {
    c = Coefficients(p.data(), count) - along;
  }
  if (c.minCoeff() > margin) return 1;
  return c.maxCoeff() < -margin ? -1 : 0;
}

/// Every coefficient p_k − r·q_k is finite: the form's size bounds hold |p_k| and |q_k|.
bool boundedSizes(const GradientForm& F, double r) { return F.sizeP + std::sqrt(3.0) * r * F.sizeQ < 1e300; }

/// No patch edge in the node: only interior minima, which need both components zero.
bool interior(const PatchNode& n) { return n.s0 > 0 && n.s1 < 1 && n.t0 > 0 && n.t1 < 1; }

/// How far a coefficient p_k − r·q_k of the point query's numerators may be from the exact one: the form's
/// errors, r's rounding (an ulp of the larger of q and the centre), and, with `reach`, every point within that
/// distance of q (it moves each coefficient by at most reach |q_k|).
double pointMargin(const GradientForm& F, const Eigen::Vector3d& q, double reach) {
  const double rn = (q - F.centre).norm();
  const double slack = 2 * kEps * (q.cwiseAbs().maxCoeff() + F.centre.cwiseAbs().maxCoeff()) * std::sqrt(3.0) + reach;
  return F.errP + (rn + reach) * F.errQ + slack * F.sizeQ * (1 + 1e-12) + 8 * kEps * (F.sizeP + (rn + reach) * F.sizeQ);
}

bool pointHoldsNoMinimum(const PatchNode& n, const PatchForest& forest, const Eigen::Vector3d& q, GradientScratch& g,
                         double negligible, double reach) {
  const GradientForm& F = gradientForm(n, forest);
  const Eigen::Vector3d r = q - F.centre;
  if (!boundedSizes(F, r.norm() + reach)) return false;
  const double margin = pointMargin(F, q, reach);
  int signs[2];
  signs[0] = combine(F.pu, r, F.qu, margin, g.u);
  if (signs[0] != 0 && interior(n)) return true;  // ∂/∂s never zero (the usual proof: v is not needed)
  signs[1] = combine(F.pv, r, F.qv, margin, g.v);
  if (interior(n)) return signs[1] != 0;
  return noMinimum(F, g.u, g.v, signs, n, margin, negligible);
}

PointGradientSigns pointGradientSigns(const PatchNode& n, const PatchForest& forest, const Eigen::Vector3d& q,
                                      GradientScratch& g) {
  const GradientForm& F = gradientForm(n, forest);
  const Eigen::Vector3d r = q - F.centre;
  PointGradientSigns out;
  if (!boundedSizes(F, r.norm())) return out;
  const double margin = pointMargin(F, q, 0);
  out.whole[0] = combine(F.pu, r, F.qu, margin, g.u);
  out.whole[1] = combine(F.pv, r, F.qv, margin, g.v);
  // A side's line of coefficients is the restriction of the numerator to it.
  const int cu = F.tu + 1, cv = F.tv + 1;
  out.along[0] = signOver(g.v, cv, 0, 0, 0, F.tv, margin);
  out.along[1] = signOver(g.v, cv, F.sv, F.sv, 0, F.tv, margin);
  out.along[2] = signOver(g.u, cu, 0, F.su, 0, 0, margin);
  out.along[3] = signOver(g.u, cu, 0, F.su, F.tu, F.tu, margin);
  return out;
}

bool supportHoldsNoMinimum(const PatchNode& n, const PatchForest& forest, const Eigen::Vector3d& d, GradientScratch& g,
                           double negligible) {
  const GradientForm& F = gradientForm(n, forest);
  if (!boundedSizes(F, d.norm())) return false;
  const double margin = F.errQ + 8 * kEps * F.sizeQ;
  const std::vector<double> none;
  const int signs[2] = {combine(none, d, F.qu, margin, g.u), combine(none, d, F.qv, margin, g.v)};
  return noMinimum(F, g.u, g.v, signs, n, margin, negligible);
}

}  // namespace unidist::nurbs
