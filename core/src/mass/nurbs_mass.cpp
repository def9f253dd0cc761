// NURBS solid: the divergence theorem turns the volume integrals into surface integrals over the rational
// Bézier patches (one per knot rectangle, exactly the surface). With x relative to the bounds centre and
// n dA = ±(Su × Sv) ds dt (outward), div(x) = 3, div(x_i x) = 4 x_i and div(x_i x_j x) = 5 x_i x_j give
//   V = 1/3 ∮ x·n,   ∫ x dV = 1/4 ∮ x (x·n),   ∫ x xᵀ dV = 1/5 ∮ x xᵀ (x·n).
// For a polynomial patch of degrees (p, q) the integrand is a polynomial of degree (5p − 1, 5q − 1), which
// ceil(5p/2) x ceil(5q/2) Gauss points integrate exactly. A rational patch gives a rational integrand
// (smooth: weights > 0): a denser rule, halved adaptively until halving no longer changes the result
// beyond rounding.
#include "mass/gauss_legendre.h"
#include "mass/mass_parts.h"
#include "mass/volume_moments.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace unidist::mass {
namespace {

constexpr double kRelativeAgreement = 1e-15;  // of size^k for a moment of length power k, per patch
constexpr int kMaxSplitDepth = 6;
constexpr int kRationalExtraPoints = 8;         // a rational integrand is not a polynomial: start denser

/// Surface integrals of g = x·n, x g and x xᵀ g over a piece of surface.
struct SurfaceSums {
  double g = 0;
  Eigen::Vector3d xg = Eigen::Vector3d::Zero();
  Eigen::Matrix3d xxg = Eigen::Matrix3d::Zero();

  SurfaceSums& operator+=(const SurfaceSums& o) {
    g += o.g;
    xg += o.xg;
    xxg += o.xxg;
    return *this;
  }
  /// Largest difference, each term divided by size^(its length power), so that they compare.
  double scaledDifference(const SurfaceSums& o, double size) const {
    const double s3 = size * size * size;
    return std::max({std::abs(g - o.g) / s3, (xg - o.xg).cwiseAbs().maxCoeff() / (s3 * size),
                     (xxg - o.xxg).cwiseAbs().maxCoeff() / (s3 * size * size)});
  }
};

struct Rect {
  double s0, s1, t0, t1;
};

class PatchIntegrator {
 public:
  PatchIntegrator(const RationalBezierPatch& patch, const Eigen::Vector3d& origin, int orientation, double size)
      : patch_(patch), origin_(origin), orientation_(orientation), size_(size) {
    const bool rational = isRational(patch);
    const int extra = rational ? kRationalExtraPoints : 0;
    ruleU_ = gaussLegendre((5 * patch.degreeU + 1) / 2 + extra);
    ruleV_ = gaussLegendre((5 * patch.degreeV + 1) / 2 + extra);
    adaptive_ = rational;
  }

  SurfaceSums integrate() const {
    const Rect whole{0, 1, 0, 1};
    const SurfaceSums estimate = rule(whole);
    return adaptive_ ? refine(whole, estimate, 0) : estimate;
  }

 private:
  static bool isRational(const RationalBezierPatch& P) {
    const double w0 = P.net.front()[3];
    return std::any_of(P.net.begin(), P.net.end(), [w0](const Eigen::Vector4d& c) { return c[3] != w0; });
  }

  /// The tensor Gauss rule on one rectangle of the patch's local parameters.
  SurfaceSums rule(const Rect& r) const {
    SurfaceSums sums;
    const double area = (r.s1 - r.s0) * (r.t1 - r.t0);
    for (std::size_t i = 0; i < ruleU_.nodes.size(); ++i)
      for (std::size_t j = 0; j < ruleV_.nodes.size(); ++j) {
        const double s = r.s0 + (r.s1 - r.s0) * ruleU_.nodes[i], t = r.t0 + (r.t1 - r.t0) * ruleV_.nodes[j];
        const SurfaceDerivatives d = patch_.derivatives(s, t);
        const Eigen::Vector3d x = d.point - origin_;
        const double w = area * ruleU_.weights[i] * ruleV_.weights[j];
        const double g = w * orientation_ * x.dot(d.du.cross(d.dv));
        sums.g += g;
        sums.xg += g * x;
        sums.xxg += g * (x * x.transpose());
      }
    return sums;
  }

  /// Compares the rectangle's estimate with the sum over its quarters; recurses into the quarters until
  /// they agree (or the depth limit: the quarters' sum is then the best estimate there is).
  SurfaceSums refine(const Rect& r, const SurfaceSums& estimate, int depth) const {
    const double sm = 0.5 * (r.s0 + r.s1), tm = 0.5 * (r.t0 + r.t1);
    const Rect quarters[4] = {{r.s0, sm, r.t0, tm}, {sm, r.s1, r.t0, tm}, {r.s0, sm, tm, r.t1}, {sm, r.s1, tm, r.t1}};
    SurfaceSums parts[4], total;
    for (int k = 0; k < 4; ++k) total += parts[k] = rule(quarters[k]);
    if (depth >= kMaxSplitDepth || total.scaledDifference(estimate, size_) <= kRelativeAgreement) return total;
    SurfaceSums refined;
    for (int k = 0; k < 4; ++k) refined += refine(quarters[k], parts[k], depth + 1);
    return refined;
  }

  const RationalBezierPatch& patch_;
  Eigen::Vector3d origin_;
  int orientation_;
  double size_;
  GaussRule ruleU_, ruleV_;
  bool adaptive_ = false;
};

}  // namespace

MassProperties nurbsMass(const NurbsModel& model) {
  VolumeMoments m;
  m.origin = model.localBounds().center();
  const double size = std::max(0.5 * model.localBounds().diagonal(), std::numeric_limits<double>::min());
  SurfaceSums total;
  for (const RationalBezierPatch& patch : model.patches())
    total += PatchIntegrator(patch, m.origin, model.orientation(), size).integrate();
  m.volume = total.g / 3;
  m.first = total.xg / 4;
  m.second = total.xxg / 5;
  return toMassProperties(m, model);
}

}  // namespace unidist::mass
