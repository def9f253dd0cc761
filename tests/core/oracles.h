// Independent truth for the distance tests: support maps and signed distances of the primitives written
// again from their definitions (not through the library), and brute-force searches built on them.
#pragma once

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace oracle {

using Vec = Eigen::Vector3d;
using Pose = Eigen::Isometry3d;

/// A primitive as the tests see it: name, sizes, and the two functions the oracles need (model frame).
struct Shape {
  std::string kind;
  double p0 = 0, p1 = 0, p2 = 0;
  Vec support(const Vec& u) const;          // argmax u·x over the solid
  double signedDistance(const Vec& q) const;  // negative inside
};

inline Vec unitOrX(const Vec& v) { return v.norm() > 0 ? Vec(v.normalized()) : Vec::UnitX(); }

inline Vec radialDir(const Vec& u) {
  const Eigen::Vector2d xy(u.x(), u.y());
  return xy.norm() > 0 ? Vec(u.x() / xy.norm(), u.y() / xy.norm(), 0) : Vec::UnitX();
}

inline Vec Shape::support(const Vec& u) const {
  auto sgn = [](double v) { return v >= 0 ? 1.0 : -1.0; };
  if (kind == "sphere") return p0 * unitOrX(u);
  if (kind == "box") return Vec(sgn(u.x()) * p0, sgn(u.y()) * p1, sgn(u.z()) * p2);
  if (kind == "capsule") return Vec(0, 0, sgn(u.z()) * p1) + p0 * unitOrX(u);
  if (kind == "cylinder") return p0 * radialDir(u) + Vec(0, 0, sgn(u.z()) * p1);
  if (kind == "cone") {
    const Vec apex(0, 0, p1), rim = p0 * radialDir(u) - Vec(0, 0, p1);
    return u.dot(apex) >= u.dot(rim) ? apex : rim;
  }
  if (kind == "torus") return p0 * radialDir(u) + p1 * unitOrX(u);
  return Vec::Zero();
}

/// Signed distance to a convex polygon in the (rho, z) half-plane (counter-clockwise vertices).
inline double polygonSignedDistance(double x, double y, const std::vector<Eigen::Vector2d>& poly) {
  bool inside = true;
  double best = 1e300;
  for (size_t i = 0; i < poly.size(); ++i) {
    const Eigen::Vector2d a = poly[i], b = poly[(i + 1) % poly.size()], e = b - a, w(x - a.x(), y - a.y());
    if (e.x() * w.y() - e.y() * w.x() < 0) inside = false;
    const double t = std::clamp(w.dot(e) / e.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (w - t * e).norm());
  }
  return inside ? -best : best;
}

inline double Shape::signedDistance(const Vec& q) const {
  const double rho = std::hypot(q.x(), q.y());
  if (kind == "sphere") return q.norm() - p0;
  if (kind == "box") {
    const Vec d = q.cwiseAbs() - Vec(p0, p1, p2);
    return d.cwiseMax(0.0).norm() + std::min(d.maxCoeff(), 0.0);
  }
  if (kind == "capsule") return Vec(q.x(), q.y(), q.z() - std::clamp(q.z(), -p1, p1)).norm() - p0;
  if (kind == "cylinder") return polygonSignedDistance(rho, q.z(), {{-p0, -p1}, {p0, -p1}, {p0, p1}, {-p0, p1}});
  if (kind == "cone") return polygonSignedDistance(rho, q.z(), {{-p0, -p1}, {p0, -p1}, {0, p1}});
  if (kind == "torus") return std::hypot(rho - p0, q.z()) - p1;
  return 0;
}

inline Vec worldSupport(const Shape& s, const Pose& X, const Vec& u_W) {
  return X * s.support(X.linear().transpose() * u_W);
}

/// Unit directions spread over the sphere (Fibonacci lattice).
inline std::vector<Vec> sphereDirections(int n) {
  std::vector<Vec> dirs;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1 - (i + 0.5) * 2.0 / n, r = std::sqrt(1 - z * z);
    dirs.emplace_back(r * std::cos(golden * i), r * std::sin(golden * i), z);
  }
  return dirs;
}

/// Support-plane overlap of A and B along u: max_A u·a − min_B u·b (> 0: moving B by this along u separates).
inline double overlapAlong(const Shape& a, const Pose& XA, const Shape& b, const Pose& XB, const Vec& u) {
  return u.dot(worldSupport(a, XA, u)) - u.dot(worldSupport(b, XB, -u));
}

/// Face normals and edge directions of a posed box, for the candidate axes of polytope pairs.
inline std::vector<Vec> boxAxes(const Shape& s, const Pose& X) {
  if (s.kind != "box") return {};
  return {X.linear().col(0), X.linear().col(1), X.linear().col(2)};
}

/// Penetration depth of two convex solids: min over directions of the support overlap. Every direction
/// gives an upper bound, so the oracle converges from above: a dense direction set, the axes where polytope
/// pairs take their minimum (box face normals and edge–edge cross products), then a shrinking pattern
/// search with many probe directions (the overlap has ridges where a few probes would stall).
inline double convexPenetration(const Shape& a, const Pose& XA, const Shape& b, const Pose& XB, Vec* bestDir = nullptr) {
  Vec best = Vec::UnitX();
  double bestValue = 1e300;
  auto consider = [&](const Vec& u) {
    const double v = overlapAlong(a, XA, b, XB, u);
    if (v < bestValue) bestValue = v, best = u;
  };
  for (const Vec& u : sphereDirections(20000)) consider(u);
  const std::vector<Vec> axesA = boxAxes(a, XA), axesB = boxAxes(b, XB);
  std::vector<Vec> candidates = axesA;
  candidates.insert(candidates.end(), axesB.begin(), axesB.end());
  for (const Vec& ea : axesA)
    for (const Vec& eb : axesB)
      if (ea.cross(eb).norm() > 1e-12) candidates.push_back(ea.cross(eb).normalized());
  for (const Vec& u : candidates) consider(u), consider(-u);
  const int probes = 48;
  for (double step = 0.02; step > 1e-13; step *= 0.5) {
    bool improved = true;
    while (improved) {
      improved = false;
      const Vec t1 = (std::abs(best.x()) < 0.6 ? Vec::UnitX() : Vec::UnitY()).cross(best).normalized();
      const Vec t2 = best.cross(t1);
      const Vec from = best;
      for (int k = 0; k < probes; ++k) {
        const double angle = 2 * M_PI * k / probes;
        const Vec u = (from + step * (std::cos(angle) * t1 + std::sin(angle) * t2)).normalized();
        const double before = bestValue;
        consider(u);
        improved = improved || bestValue < before;
      }
    }
  }
  if (bestDir) *bestDir = best;
  return bestValue;
}

/// Distance between the centre circle of torus T (pose XT) and solid S, minus the tube radius: the separation
/// of torus and S when positive. Dense angles, then golden-section refinement of the best brackets.
inline double torusSeparation(const Shape& torus, const Pose& XT, const Shape& s, const Pose& XS) {
  auto g = [&](double th) {
    const Vec c = XT * Vec(torus.p0 * std::cos(th), torus.p0 * std::sin(th), 0);
    return s.signedDistance(XS.inverse() * c);
  };
  const int n = 20000;
  std::vector<double> values(n);
  for (int i = 0; i < n; ++i) values[i] = g(2 * M_PI * i / n);
  double best = 1e300;
  for (int i = 0; i < n; ++i) {
    const int prev = (i + n - 1) % n, next = (i + 1) % n;
    if (values[i] > values[prev] || values[i] > values[next]) continue;
    double lo = 2 * M_PI * (i - 1) / n, hi = 2 * M_PI * (i + 1) / n;
    const double ratio = (std::sqrt(5.0) - 1) / 2;
    for (int k = 0; k < 80; ++k) {
      const double m1 = hi - ratio * (hi - lo), m2 = lo + ratio * (hi - lo);
      if (g(m1) < g(m2)) hi = m2; else lo = m1;
    }
    best = std::min({best, g(0.5 * (lo + hi)), values[i]});
  }
  return best - torus.p1;
}

inline Pose randomPose(std::mt19937_64& rng, double extent) {
  std::normal_distribution<double> n01;
  std::uniform_real_distribution<double> u(-extent, extent);
  Eigen::Quaterniond q(n01(rng), n01(rng), n01(rng), n01(rng));
  q.normalize();
  Pose X = Pose::Identity();
  X.linear() = q.toRotationMatrix();
  X.translation() = Vec(u(rng), u(rng), u(rng));
  return X;
}

inline Vec randomUnit(std::mt19937_64& rng) {
  std::normal_distribution<double> n01;
  return Vec(n01(rng), n01(rng), n01(rng)).normalized();
}

}  // namespace oracle
