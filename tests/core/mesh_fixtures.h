// Test meshes (tessellated sphere, box, torus, wavy sheet) and independent truth for the mesh tests: a
// point–triangle distance written again (a 2×2 normal-equation solve in long double, then clamped segments),
// brute force over all triangles, and a brute-force winding number in long double.
#pragma once

#include "unidist/mesh.h"

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <vector>

namespace meshfix {

using Vec = Eigen::Vector3d;
using Tri = std::array<std::uint32_t, 3>;
using LD = long double;
using VecL = Eigen::Matrix<long double, 3, 1>;

struct Soup {
  std::vector<Vec> vertices;
  std::vector<Tri> triangles;
};

inline VecL toL(const Vec& v) { return v.cast<long double>(); }
inline Vec toD(const VecL& v) { return v.cast<double>(); }

/// Squared distance from q to segment [a, b] (long double).
inline LD segmentSq(const VecL& q, const VecL& a, const VecL& b) {
  const VecL e = b - a;
  const LD ee = e.squaredNorm();
  LD t = ee > 0 ? (q - a).dot(e) / ee : 0;
  t = std::clamp(t, (LD)0, (LD)1);
  return ((a - q) + t * e).squaredNorm();  // relative to q first: keeps digits far from the origin
}

/// Squared distance from q to triangle (a, b, c): the unconstrained minimiser of |a + s e0 + t e1 − q|² when it
/// lies in the triangle, else the best edge.
inline LD triangleSq(const Vec& qd, const Vec& ad, const Vec& bd, const Vec& cd) {
  const VecL q = toL(qd), a = toL(ad), b = toL(bd), c = toL(cd);
  const VecL e0 = b - a, e1 = c - a, w = a - q;
  const LD A = e0.dot(e0), B = e0.dot(e1), C = e1.dot(e1), D = e0.dot(w), E = e1.dot(w);
  const LD det = A * C - B * B;
  if (det > 0) {
    const LD s = (B * E - C * D) / det, t = (B * D - A * E) / det;
    if (s >= 0 && t >= 0 && s + t <= 1) return (w + s * e0 + t * e1).squaredNorm();
  }
  return std::min({segmentSq(q, a, b), segmentSq(q, b, c), segmentSq(q, c, a)});
}

/// Unsigned distance to the soup by brute force.
inline double bruteDistance(const Soup& s, const Vec& q) {
  LD best = std::numeric_limits<LD>::infinity();
  for (const Tri& t : s.triangles)
    best = std::min(best, triangleSq(q, s.vertices[t[0]], s.vertices[t[1]], s.vertices[t[2]]));
  return static_cast<double>(std::sqrt(best));
}

/// Winding number by brute force (van Oosterom–Strackee in long double).
inline double bruteWinding(const Soup& s, const Vec& qd) {
  const VecL q = toL(qd);
  LD sum = 0;
  for (const Tri& t : s.triangles) {
    const VecL a = toL(s.vertices[t[0]]) - q, b = toL(s.vertices[t[1]]) - q, c = toL(s.vertices[t[2]]) - q;
    const LD la = a.norm(), lb = b.norm(), lc = c.norm();
    sum += 2 * std::atan2(a.dot(b.cross(c)), la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb);
  }
  return static_cast<double>(sum / (4 * M_PIl));
}

inline Soup scaled(Soup s, double k, const Vec& shift = Vec::Zero()) {
  for (Vec& v : s.vertices) v = k * v + shift;
  return s;
}

inline Soup reversed(Soup s) {
  for (Tri& t : s.triangles) std::swap(t[1], t[2]);
  return s;
}

/// Icosahedron subdivided `levels` times, vertices on the sphere of radius r (outward).
inline Soup icosphere(double r, int levels) {
  const double g = (1 + std::sqrt(5.0)) / 2;
  Soup s;
  s.vertices = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  s.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (Vec& v : s.vertices) v.normalize();
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      s.vertices.push_back((s.vertices[a] + s.vertices[b]).normalized());
      const auto id = static_cast<std::uint32_t>(s.vertices.size() - 1);
      mid[key] = id;
      return id;
    };
    std::vector<Tri> next;
    for (const Tri& t : s.triangles) {
      const std::uint32_t ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
      next.push_back({t[0], ab, ca});
      next.push_back({t[1], bc, ab});
      next.push_back({t[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    s.triangles = std::move(next);
  }
  for (Vec& v : s.vertices) v *= r;
  return s;
}

/// Box [-h, h] with every face split into an n × n grid of squares, two triangles each (outward). Shared
/// vertices are shared indices.
inline Soup gridBox(const Vec& h, int n) {
  Soup s;
  std::map<std::array<int, 3>, std::uint32_t> ids;
  auto vertex = [&](int i, int j, int k) {  // integer lattice 0..n per axis
    const std::array<int, 3> key = {i, j, k};
    auto it = ids.find(key);
    if (it != ids.end()) return it->second;
    s.vertices.emplace_back(-h.x() + 2 * h.x() * i / n, -h.y() + 2 * h.y() * j / n, -h.z() + 2 * h.z() * k / n);
    const auto id = static_cast<std::uint32_t>(s.vertices.size() - 1);
    ids[key] = id;
    return id;
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
          auto at = [&](int da, int db) {
            std::array<int, 3> c{};
            c[axis] = side * n;
            c[u] = a + da;
            c[v] = b + db;
            return vertex(c[0], c[1], c[2]);
          };
          // (u, v, axis) is right-handed: counter-clockwise in (u, v) faces +axis.
          const std::uint32_t p00 = at(0, 0), p10 = at(1, 0), p11 = at(1, 1), p01 = at(0, 1);
          if (side == 1) {
            s.triangles.push_back({p00, p10, p11});
            s.triangles.push_back({p00, p11, p01});
          } else {
            s.triangles.push_back({p00, p11, p10});
            s.triangles.push_back({p00, p01, p11});
          }
        }
    }
  return s;
}

/// Torus about z (major R, tube r), nu × nv quads split in two (outward).
inline Soup torus(double R, double r, int nu, int nv) {
  Soup s;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * M_PI * i / nu, v = 2 * M_PI * j / nv;
      s.vertices.emplace_back((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
    }
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>(((i + nu) % nu) * nv + (j + nv) % nv); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      s.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      s.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return s;
}

/// Open sheet z = height(x, y) over [-half, half]², n × n quads split in two.
template <class Height>
Soup heightSheet(double half, int n, Height height) {
  Soup s;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double x = -half + 2 * half * i / n, y = -half + 2 * half * j / n;
      s.vertices.emplace_back(x, y, height(x, y));
    }
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>(i * (n + 1) + j); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      s.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      s.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return s;
}

/// Open sheet z = 0.2 sin(3x) cos(2y) over [-1, 1]², n × n quads.
inline Soup wavySheet(int n) {
  return heightSheet(1.0, n, [](double x, double y) { return 0.2 * std::sin(3 * x) * std::cos(2 * y); });
}

/// Random points: near the surface (a surface point moved up to `near` along a random direction) and
/// spread over the bounding box grown by `margin` of its size.
inline std::vector<Vec> queryPoints(const Soup& s, int count, double near, double margin, std::mt19937_64& rng) {
  Vec lo = s.vertices[0], hi = s.vertices[0];
  for (const Vec& v : s.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  const double size = (hi - lo).norm();
  std::uniform_real_distribution<double> u01(0, 1);
  std::normal_distribution<double> n01;
  std::vector<Vec> out;
  for (int i = 0; i < count; ++i) {
    if (i % 2 == 0) {
      const Tri& t = s.triangles[rng() % s.triangles.size()];
      double a = u01(rng), b = u01(rng);
      if (a + b > 1) a = 1 - a, b = 1 - b;
      const Vec p = s.vertices[t[0]] + a * (s.vertices[t[1]] - s.vertices[t[0]]) + b * (s.vertices[t[2]] - s.vertices[t[0]]);
      const Vec dir = Vec(n01(rng), n01(rng), n01(rng)).normalized();
      out.push_back(p + near * size * u01(rng) * dir);
    } else {
      Vec p;
      for (int k = 0; k < 3; ++k) p[k] = lo[k] - margin * size + (hi[k] - lo[k] + 2 * margin * size) * u01(rng);
      out.push_back(p);
    }
  }
  return out;
}

/// Exact (long double) squared distances between segments and between triangles, for brute-force oracles.
inline LD segSegSq(const VecL& p1, const VecL& q1, const VecL& p2, const VecL& q2) {
  LD best = std::min({segmentSq(p1, p2, q2), segmentSq(q1, p2, q2), segmentSq(p2, p1, q1),
                      segmentSq(q2, p1, q1)});
  const VecL d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const LD a = d1.dot(d1), e = d2.dot(d2), b = d1.dot(d2), c = d1.dot(r), f = d2.dot(r);
  const LD det = a * e - b * b;
  if (det > 1e-15L * a * e) {
    const LD s = (b * f - c * e) / det, t = (a * f - b * c) / det;
    if (s >= 0 && s <= 1 && t >= 0 && t <= 1) best = std::min(best, (r + s * d1 - t * d2).squaredNorm());
  }
  return best;
}

/// Whether edge [p, q] crosses triangle (a, b, c).
inline bool edgeCrosses(const VecL& p, const VecL& q, const VecL& a, const VecL& b, const VecL& c) {
  const VecL n = (b - a).cross(c - a);
  const LD dp = n.dot(p - a), dq = n.dot(q - a);
  if (dp * dq > 0 || (dp == 0 && dq == 0)) return false;
  const VecL x = p + (dp / (dp - dq)) * (q - p);
  const VecL e0 = b - a, e1 = c - a, w = x - a;
  const LD A = e0.dot(e0), B = e0.dot(e1), C = e1.dot(e1), D = e0.dot(w), E = e1.dot(w);
  const LD det = A * C - B * B;
  if (!(det > 0)) return false;
  const LD s = (C * D - B * E) / det, t = (A * E - B * D) / det;
  return s >= 0 && t >= 0 && s + t <= 1;
}

/// Squared distance of two triangles. crossB = false skips A's edges crossing B: for a B of (near) zero area
/// (a segment as (p, q, q)), whose plane is noise, such a crossing is never needed (B's own edges carry it).
inline LD triTriSq(const std::array<VecL, 3>& A, const std::array<VecL, 3>& B, bool crossB = true) {
  for (int i = 0; i < 3; ++i)
    if ((crossB && edgeCrosses(A[i], A[(i + 1) % 3], B[0], B[1], B[2])) ||
        edgeCrosses(B[i], B[(i + 1) % 3], A[0], A[1], A[2]))
      return 0;
  LD best = std::numeric_limits<LD>::infinity();
  for (int i = 0; i < 3; ++i) {
    best = std::min(best, meshfix::triangleSq(toD(A[i]), toD(B[0]), toD(B[1]), toD(B[2])));
    best = std::min(best, meshfix::triangleSq(toD(B[i]), toD(A[0]), toD(A[1]), toD(A[2])));
    for (int j = 0; j < 3; ++j) best = std::min(best, segSegSq(A[i], A[(i + 1) % 3], B[j], B[(j + 1) % 3]));
  }
  return best;
}

inline unidist::TriangleMesh makeMesh(const Soup& s) { return unidist::TriangleMesh(s.vertices, s.triangles); }

}  // namespace meshfix
