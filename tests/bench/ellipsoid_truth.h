// Truth for the penetration depth of two ellipsoids (convex): min over unit n of h_A(n) + h_B(−n), from their
// analytic support functions; and the exact rational ellipsoid as a NURBS surface. Shared by the convex-depth
// tests and benchmark.
#pragma once

#include "core/nurbs_fixtures.h"
#include "unidist/nurbs.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace ellipsoid_truth {

using Vec = Eigen::Vector3d;

/// A rational ellipsoid with semi-axes e (the exact sphere's net scaled per axis).
inline unidist::NurbsSurface surface(const Vec& e) {
  const unidist::NurbsSurface s = nurbs_fixtures::sphereSurface(1);
  nurbs_fixtures::Net net(static_cast<std::size_t>(s.countU()));
  for (int i = 0; i < s.countU(); ++i)
    for (int j = 0; j < s.countV(); ++j) {
      const Eigen::Vector4d c = s.controlPoint(i, j);
      net[static_cast<std::size_t>(i)].emplace_back(e.x() * c.x(), e.y() * c.y(), e.z() * c.z(), c[3]);
    }
  return {s.degreeU(), s.degreeV(), s.knotsU(), s.knotsV(), net};
}

struct Ellipsoid {
  Vec axes;
  Eigen::Isometry3d pose;
  /// Support function: the ellipsoid is {pose·(diag(axes) u) : |u| <= 1}.
  double support(const Vec& n) const {
    return n.dot(pose.translation()) + (axes.asDiagonal() * (pose.linear().transpose() * n)).norm();
  }
};

/// min over unit n of h_A(n) + h_B(−n): the largest of a dense set of directions' minima, each polished by
/// projected gradient descent with backtracking (the function is smooth: both ellipsoids are strictly convex).
inline double depth(const Ellipsoid& a, const Ellipsoid& b) {
  const auto f = [&](const Vec& n) { return a.support(n) + b.support(-n); };
  constexpr int kDirections = 4000;
  std::vector<std::pair<double, Vec>> starts;
  for (int k = 0; k < kDirections; ++k) {  // Fibonacci sphere
    const double z = 1 - (2 * k + 1.0) / kDirections, r = std::sqrt(1 - z * z), phi = k * 2.399963229728653;
    const Vec n(r * std::cos(phi), r * std::sin(phi), z);
    starts.emplace_back(f(n), n);
  }
  std::partial_sort(starts.begin(), starts.begin() + 8, starts.end(),
                    [](const auto& x, const auto& y) { return x.first < y.first; });
  double best = starts.front().first;
  for (int s = 0; s < 8; ++s) {
    Vec n = starts[static_cast<std::size_t>(s)].second;
    double value = f(n), step = 0.1;
    for (int it = 0; it < 4000 && step > 1e-16; ++it) {
      const double h = 1e-7;
      Vec g;
      for (int i = 0; i < 3; ++i) g[i] = (f((n + h * Vec::Unit(i)).normalized()) - f((n - h * Vec::Unit(i)).normalized())) / (2 * h);
      g -= g.dot(n) * n;
      if (g.norm() == 0) break;
      const Vec trial = (n - step * g.normalized()).normalized();
      if (const double v = f(trial); v < value) {
        value = v;
        n = trial;
        step *= 1.5;
      } else {
        step *= 0.5;
      }
    }
    best = std::min(best, value);
  }
  return best;
}

}  // namespace ellipsoid_truth
