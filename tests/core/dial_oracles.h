// Brute-force truth for the tolerance-dial cases (tests/core/dial_cases.h), independent of the library:
// long-double triangle–triangle and segment–triangle distances (meshfix::triTriSq, tests/core/mesh_fixtures.h),
// mesh signed distance (distance and winding number over every
// triangle), the exact penetration depth of two boxes (15 separating axes), the distance from a circle to a mesh
// (a torus is the set of points within its tube radius of that circle), and point samples of known surfaces.
#pragma once

#include "core/mesh_fixtures.h"
#include "core/oracles.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace dial {

using meshfix::LD;
using meshfix::Soup;
using meshfix::Tri;
using meshfix::triTriSq;
using meshfix::VecL;
using Vec = Eigen::Vector3d;
using Pose = Eigen::Isometry3d;

using meshfix::toD;

inline std::vector<VecL> posed(const Soup& s, const Pose& X) {
  std::vector<VecL> out;
  for (const Vec& v : s.vertices) out.push_back(X.cast<LD>() * meshfix::toL(v));
  return out;
}

inline std::array<VecL, 3> corners(const std::vector<VecL>& p, const Tri& t) { return {p[t[0]], p[t[1]], p[t[2]]}; }

/// Unsigned distance between two posed meshes; a triangle pair is skipped only when balls around both
/// triangles prove it farther than the best so far.
inline double meshMeshDistance(const Soup& a, const Pose& Xa, const Soup& b, const Pose& Xb) {
  const std::vector<VecL> pa = posed(a, Xa), pb = posed(b, Xb);
  auto balls = [](const Soup& s, const std::vector<VecL>& p) {
    std::vector<std::pair<VecL, LD>> out;
    for (const Tri& t : s.triangles) {
      const VecL c = (p[t[0]] + p[t[1]] + p[t[2]]) / 3;
      out.push_back({c, 1.000001L * std::max({(p[t[0]] - c).norm(), (p[t[1]] - c).norm(), (p[t[2]] - c).norm()})});
    }
    return out;
  };
  const auto ba = balls(a, pa), bb = balls(b, pb);
  LD best = std::numeric_limits<LD>::infinity();
  for (std::size_t i = 0; i < a.triangles.size(); ++i)
    for (std::size_t j = 0; j < b.triangles.size(); ++j) {
      const LD gap = (ba[i].first - bb[j].first).norm() - ba[i].second - bb[j].second;
      if (gap > 0 && gap * gap > best * 1.000001L) continue;
      best = std::min(best, triTriSq(corners(pa, a.triangles[i]), corners(pb, b.triangles[j])));
    }
  return static_cast<double>(std::sqrt(best));
}

/// Unsigned distance from segment [p, q] to a posed mesh.
inline double segmentMeshDistance(const Vec& p, const Vec& q, const Soup& s, const Pose& X) {
  const std::vector<VecL> ps = posed(s, X);
  const std::array<VecL, 3> seg = {meshfix::toL(p), meshfix::toL(q), meshfix::toL(q)};
  LD best = std::numeric_limits<LD>::infinity();
  for (const Tri& t : s.triangles) best = std::min(best, triTriSq(corners(ps, t), seg, false));
  return static_cast<double>(std::sqrt(best));
}

/// Signed distance from a world point to a posed closed mesh: negative inside (winding number).
inline double meshSignedDistance(const Soup& s, const Pose& X, const Vec& q_W) {
  const Vec q = X.inverse() * q_W;
  const double d = meshfix::bruteDistance(s, q);
  return std::abs(meshfix::bruteWinding(s, q)) > 0.5 ? -d : d;
}

/// Exact penetration depth (positive) of two overlapping boxes: the least overlap over the 15 separating axes.
inline double boxBoxDepth(const oracle::Shape& a, const Pose& Xa, const oracle::Shape& b, const Pose& Xb) {
  std::vector<Vec> axes = {Xa.linear().col(0), Xa.linear().col(1), Xa.linear().col(2),
                           Xb.linear().col(0), Xb.linear().col(1), Xb.linear().col(2)};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const Vec c = Xa.linear().col(i).cross(Xb.linear().col(j));
      if (c.norm() > 1e-9) axes.push_back(c.normalized());
    }
  double best = std::numeric_limits<double>::infinity();
  for (const Vec& u : axes)
    best = std::min({best, oracle::overlapAlong(a, Xa, b, Xb, u), oracle::overlapAlong(a, Xa, b, Xb, -u)});
  return best;
}

/// A circle in the world: centre, unit axis, radius.
struct Circle {
  Vec centre, axis;
  double radius;
  Vec at(double angle) const {
    const Vec e1 = axis.unitOrthogonal(), e2 = axis.cross(e1);
    return centre + radius * (std::cos(angle) * e1 + std::sin(angle) * e2);
  }
};

/// Distance from a circle to a posed mesh: every triangle sampled at 256 angles; a triangle whose samples,
/// less the most the distance can drop between two samples (radius × half the step: it is radius-Lipschitz
/// in the angle), cannot beat the best is dropped; the rest are sampled at 4096 angles and every sampled
/// local minimum is refined by golden section.
inline double circleMeshDistance(const Circle& c, const Soup& s, const Pose& X) {
  const std::vector<VecL> ps = posed(s, X);
  auto at = [&](const Tri& t, double angle) {
    return std::sqrt(static_cast<double>(meshfix::triangleSq(c.at(angle), toD(ps[t[0]]), toD(ps[t[1]]), toD(ps[t[2]]))));
  };
  constexpr int kCoarse = 256, kFine = 4096;
  std::vector<double> coarse(s.triangles.size(), std::numeric_limits<double>::infinity());
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < s.triangles.size(); ++i) {
    for (int k = 0; k < kCoarse; ++k) coarse[i] = std::min(coarse[i], at(s.triangles[i], 2 * M_PI * k / kCoarse));
    best = std::min(best, coarse[i]);
  }
  const double slack = c.radius * M_PI / kCoarse;
  for (std::size_t i = 0; i < s.triangles.size(); ++i) {
    if (coarse[i] - slack > best) continue;
    const Tri& t = s.triangles[i];
    std::vector<double> v(kFine);
    for (int k = 0; k < kFine; ++k) v[static_cast<std::size_t>(k)] = at(t, 2 * M_PI * k / kFine);
    for (int k = 0; k < kFine; ++k) {
      const double here = v[static_cast<std::size_t>(k)];
      if (here > v[static_cast<std::size_t>((k + kFine - 1) % kFine)] || here > v[static_cast<std::size_t>((k + 1) % kFine)])
        continue;
      double lo = 2 * M_PI * (k - 1) / kFine, hi = 2 * M_PI * (k + 1) / kFine;
      const double g = 0.5 * (std::sqrt(5.0) - 1);
      for (int it = 0; it < 80; ++it) {
        const double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
        if (at(t, x1) < at(t, x2)) {
          hi = x2;
        } else {
          lo = x1;
        }
      }
      best = std::min({best, here, at(t, 0.5 * (lo + hi))});
    }
  }
  return best;
}

/// Distance from a point to a circle (as a curve).
inline double pointCircle(const Vec& p, const Circle& c) {
  const Vec d = p - c.centre;
  const double h = d.dot(c.axis);
  return std::hypot(h, (d - h * c.axis).norm() - c.radius);
}

/// n points spread over the sphere of radius r (Fibonacci lattice).
inline std::vector<Vec> spherePoints(double r, int n) {
  std::vector<Vec> out;
  for (const Vec& u : oracle::sphereDirections(n)) out.push_back(r * u);
  return out;
}

/// n points spread over the torus (major R, tube a) about z: golden-angle steps in both angles.
inline std::vector<Vec> torusPoints(double R, double a, int n) {
  std::vector<Vec> out;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double u = 2 * M_PI * (i + 0.5) / n, v = golden * i * 7;
    out.emplace_back((R + a * std::cos(v)) * std::cos(u), (R + a * std::cos(v)) * std::sin(u), a * std::sin(v));
  }
  return out;
}

}  // namespace dial
