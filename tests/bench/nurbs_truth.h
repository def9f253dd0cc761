// Placements of exact rational tori and spheres whose surface–surface distance is known: a torus is the set of
// points within a of its core circle, so two separated tubes are (circle–circle distance) − a1 − a2 apart, and a
// sphere (c, r) is dist(c, circle) − a − r from a torus. The circle–circle distance is a one-dimensional
// minimisation (dense angle sampling, then golden-section refinement of every sampled local minimum);
// closedFormError() checks it where a closed form exists. Interpenetrating tori with coplanar or coaxial core
// circles: the circles' distance is 1-Lipschitz in the translation and grows at rate 1 along their closest-point
// line, so the penetration depth (minimum translation) is exactly 2a minus it. Benchmark-only.
#pragma once

#include "core/nurbs_fixtures.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace nurbs_truth {

using Vec = Eigen::Vector3d;

struct Circle {
  Vec centre, axis;  // axis unit
  double radius;
};

/// Distance from p to the circle (as a curve).
inline double pointCircle(const Vec& p, const Circle& c) {
  const Vec d = p - c.centre;
  const double h = d.dot(c.axis);
  const double rho = (d - h * c.axis).norm();
  return std::hypot(h, rho - c.radius);
}

/// A place around the tube of a torus about z whose core circle (radius R) is centred at the origin: `around` the
/// axis, `across` the tube from the outward radial (0 outside, π/2 above, π in the hole). point(R, h) is h from the
/// core circle (h < R), along out().
struct TubePlace {
  double around, across;
  Vec radial() const { return {std::cos(around), std::sin(around), 0}; }
  Vec out() const { return std::cos(across) * radial() + std::sin(across) * Vec::UnitZ(); }
  Vec point(double R, double h) const { return R * radial() + h * out(); }
};

inline Vec onCircle(const Circle& c, double angle) {
  const Vec e1 = c.axis.unitOrthogonal(), e2 = c.axis.cross(e1);
  return c.centre + c.radius * (std::cos(angle) * e1 + std::sin(angle) * e2);
}

inline double circleCircle(const Circle& a, const Circle& b) {
  constexpr int kSamples = 4096;
  const double step = 2 * M_PI / kSamples;
  auto f = [&](double t) { return pointCircle(onCircle(a, t), b); };
  std::vector<double> v(kSamples);
  for (int k = 0; k < kSamples; ++k) v[static_cast<std::size_t>(k)] = f(k * step);
  double best = *std::min_element(v.begin(), v.end());
  for (int k = 0; k < kSamples; ++k) {
    const double prev = v[static_cast<std::size_t>((k + kSamples - 1) % kSamples)];
    const double next = v[static_cast<std::size_t>((k + 1) % kSamples)];
    if (v[static_cast<std::size_t>(k)] > prev || v[static_cast<std::size_t>(k)] > next) continue;
    double lo = (k - 1) * step, hi = (k + 1) * step;  // golden section on the bracket around the sample
    const double g = 0.5 * (std::sqrt(5.0) - 1);
    for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
      const double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
      if (f(x1) < f(x2)) {
        hi = x2;
      } else {
        lo = x1;
      }
    }
    best = std::min(best, f(0.5 * (lo + hi)));
  }
  return best;
}

/// Largest error of circleCircle on placements with a closed form (coaxial and coplanar circles, tilted copies).
inline double closedFormError() {
  const Circle a{Vec::Zero(), Vec::UnitZ(), 1};
  double worst = 0;
  for (double h : {0.1, 0.7, 3.0}) {
    worst = std::max(worst, std::abs(circleCircle(a, {Vec(0, 0, h), Vec::UnitZ(), 1}) - h));          // coaxial
    worst = std::max(worst, std::abs(circleCircle(a, {Vec(2 + h, 0, 0), Vec::UnitZ(), 1}) - h));      // coplanar
    worst = std::max(worst, std::abs(circleCircle(a, {Vec(0, 0, h), Vec::UnitZ(), 0.5}) - std::hypot(h, 0.5)));
  }
  return worst;
}

/// Two solid NURBS models A (at the origin) and B (at X_WB), and their exact distance.
struct Placement {
  const char* name;
  unidist::NurbsSurface a, b;
  Eigen::Isometry3d X_WB;
  double truth;
};

inline Eigen::Isometry3d pose(const Vec& t, const Eigen::AngleAxisd& r = Eigen::AngleAxisd(0, Vec::UnitZ())) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translate(t);
  X.rotate(r);
  return X;
}

/// Tori R = 1, a = 0.25 (A about z at the origin); spheres of radius 0.4.
inline std::vector<Placement> placements() {
  const double R = 1, a = 0.25, rs = 0.4;
  const Circle ca{Vec::Zero(), Vec::UnitZ(), R};
  auto circleOf = [&](const Eigen::Isometry3d& X) { return Circle{X.translation(), X.linear() * Vec::UnitZ(), R}; };
  auto torusPair = [&](const char* name, const Eigen::Isometry3d& X) {
    return Placement{name, nurbs_fixtures::torusSurface(R, a), nurbs_fixtures::torusSurface(R, a), X,
                     circleCircle(ca, circleOf(X)) - 2 * a};
  };
  auto spherePair = [&](const char* name, const Vec& c) {
    return Placement{name, nurbs_fixtures::torusSurface(R, a), nurbs_fixtures::sphereSurface(rs), pose(c),
                     pointCircle(c, ca) - a - rs};
  };
  const Eigen::AngleAxisd upright(M_PI / 2, Vec::UnitX());
  return {
      torusPair("torus-torus coaxial", pose(Vec(0, 0, 0.7))),
      torusPair("torus-torus side", pose(Vec(2.7, 0, 0))),
      torusPair("torus-torus tilted", pose(Vec(2.6, 0.3, 0.4), Eigen::AngleAxisd(0.7, Vec(1, 1, 0).normalized()))),
      torusPair("torus-torus linked offset", pose(Vec(1.0, 0.1, 0.05), upright)),
      torusPair("torus-torus side overlap", pose(Vec(2.3, 0, 0))),
      torusPair("torus-torus coaxial overlap", pose(Vec(0, 0, 0.35))),
      spherePair("torus-sphere above", Vec(0.3, 0.2, 0.9)),
      spherePair("torus-sphere in hole", Vec(0, 0, 0.05)),
  };
}

}  // namespace nurbs_truth
