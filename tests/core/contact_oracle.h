// Brute-force truth for the contact search: every local minimum of distance between two triangle soups, found
// independently of the library. Candidates are all vertex–triangle pairs (both ways) and all edge–edge pairs
// with both closest points strictly inside the edges, in long double. A candidate (p on A, q on B, d = |q − p|)
// is a local minimum (first order: mutually locally closest) when every triangle of A that holds p is no closer
// to q than d, and every triangle of B that holds q no closer to p; for a solid, the segment must also leave it
// (p + h·(q − p)/d outside A, q − h·(q − p)/d outside B, decided by the winding number). Generic positions only:
// no face-on-face contacts (the library keeps only their corners there, which this oracle does not model).
#pragma once

#include "core/mesh_fixtures.h"

#include <vector>

namespace contactoracle {

using meshfix::LD;
using meshfix::Soup;
using meshfix::Vec;
using meshfix::VecL;

struct Minimum {
  Vec pA, pB;
  double distance;
};

using meshfix::toD;

/// Closest point of segment [a, b] to q.
inline VecL segmentPoint(const VecL& q, const VecL& a, const VecL& b) {
  const VecL e = b - a;
  LD t = e.squaredNorm() > 0 ? (q - a).dot(e) / e.squaredNorm() : 0;
  t = std::clamp(t, (LD)0, (LD)1);
  return a + t * e;
}

/// Closest point of triangle (a, b, c) to q: the plane's foot when inside, else the best edge point.
inline VecL trianglePoint(const VecL& q, const VecL& a, const VecL& b, const VecL& c) {
  const VecL e0 = b - a, e1 = c - a, w = a - q;
  const LD A = e0.dot(e0), B = e0.dot(e1), C = e1.dot(e1), D = e0.dot(w), E = e1.dot(w);
  const LD det = A * C - B * B;
  const LD s = (B * E - C * D) / det, t = (B * D - A * E) / det;
  if (s >= 0 && t >= 0 && s + t <= 1) return a + s * e0 + t * e1;
  VecL best = segmentPoint(q, a, b);
  for (const VecL& x : {segmentPoint(q, b, c), segmentPoint(q, c, a)})
    if ((x - q).squaredNorm() < (best - q).squaredNorm()) best = x;
  return best;
}

class Oracle {
 public:
  Oracle(const Soup& a, const Soup& b, bool solidA, bool solidB, double size)
      : a_(a), b_(b), solidA_(solidA), solidB_(solidB), size_(size) {}

  /// Every local minimum with distance <= margin, duplicates (same points) merged.
  std::vector<Minimum> minima(double margin) const {
    std::vector<Minimum> out;
    for (int side = 0; side < 2; ++side) {
      const Soup& s = side == 0 ? a_ : b_;
      const Soup& o = side == 0 ? b_ : a_;
      for (const Vec& v : s.vertices)
        for (const auto& t : o.triangles) {
          const VecL q = trianglePoint(meshfix::toL(v), meshfix::toL(o.vertices[t[0]]), meshfix::toL(o.vertices[t[1]]),
                                       meshfix::toL(o.vertices[t[2]]));
          if (side == 0)
            consider(meshfix::toL(v), q, margin, out);
          else
            consider(q, meshfix::toL(v), margin, out);
        }
    }
    for (const auto& ta : a_.triangles)
      for (const auto& tb : b_.triangles)
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) {
            const VecL p1 = meshfix::toL(a_.vertices[ta[i]]), q1 = meshfix::toL(a_.vertices[ta[(i + 1) % 3]]);
            const VecL p2 = meshfix::toL(b_.vertices[tb[j]]), q2 = meshfix::toL(b_.vertices[tb[(j + 1) % 3]]);
            const VecL d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
            const LD A = d1.dot(d1), E = d2.dot(d2), B = d1.dot(d2), C = d1.dot(r), F = d2.dot(r);
            const LD det = A * E - B * B;
            if (!(det > 1e-12L * A * E)) continue;
            const LD s = (B * F - C * E) / det, t = (A * F - B * C) / det;
            if (s > 0 && s < 1 && t > 0 && t < 1) consider(p1 + s * d1, p2 + t * d2, margin, out);
          }
    return out;
  }

 private:
  /// Whether every triangle of soup s holding x is at least d − slack from y.
  bool locallyClosest(const Soup& s, const VecL& x, const VecL& y, LD d) const {
    for (const auto& t : s.triangles) {
      const VecL a = meshfix::toL(s.vertices[t[0]]), b = meshfix::toL(s.vertices[t[1]]);
      const VecL c = meshfix::toL(s.vertices[t[2]]);
      if ((trianglePoint(x, a, b, c) - x).norm() > 1e-12L * size_) continue;  // does not hold x
      if ((trianglePoint(y, a, b, c) - y).norm() < d - 1e-10L * size_) return false;
    }
    return true;
  }

  void consider(const VecL& p, const VecL& q, double margin, std::vector<Minimum>& out) const {
    const LD d = (q - p).norm();
    if (d > margin || d < 1e-9L * size_) return;
    if (!locallyClosest(a_, p, q, d) || !locallyClosest(b_, q, p, d)) return;
    const VecL u = (q - p) / d;
    const LD h = 1e-6L * size_;
    if (solidA_ && meshfix::bruteWinding(a_, toD(p + h * u)) > 0.5) return;
    if (solidB_ && meshfix::bruteWinding(b_, toD(q - h * u)) > 0.5) return;
    const Minimum m{toD(p), toD(q), static_cast<double>(d)};
    for (const Minimum& k : out)
      if ((k.pA - m.pA).norm() < 1e-9 * size_ && (k.pB - m.pB).norm() < 1e-9 * size_) return;
    out.push_back(m);
  }

  Soup a_, b_;
  bool solidA_, solidB_;
  double size_;
};

}  // namespace contactoracle
