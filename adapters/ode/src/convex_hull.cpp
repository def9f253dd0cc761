#include "convex_hull.h"

#include "unidist/types.h"

#include <algorithm>
#include <set>
#include <utility>

namespace unidist::odeadapt {
namespace {

using Tri = std::array<std::uint32_t, 3>;
using Vec = Eigen::Vector3d;

double planeDistance(const std::vector<Vec>& p, const Tri& t, const Vec& q) {
  const Vec n = (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]);
  return n.dot(q - p[t[0]]) / n.norm();
}

std::uint32_t farthestFrom(const std::vector<Vec>& p, double (*measure)(const std::vector<Vec>&, const Vec&,
                                                                          const std::array<std::uint32_t, 3>&),
                           const std::array<std::uint32_t, 3>& ref) {
  std::uint32_t best = 0;
  double bestValue = -1;
  for (std::uint32_t i = 0; i < p.size(); ++i) {
    const double v = measure(p, p[i], ref);
    if (v > bestValue) bestValue = v, best = i;
  }
  return best;
}

double fromPoint(const std::vector<Vec>& p, const Vec& q, const Tri& r) { return (q - p[r[0]]).norm(); }
double fromLine(const std::vector<Vec>& p, const Vec& q, const Tri& r) {
  return (q - p[r[0]]).cross(p[r[1]] - p[r[0]]).norm();
}
double fromPlane(const std::vector<Vec>& p, const Vec& q, const Tri& r) {
  return std::abs((p[r[1]] - p[r[0]]).cross(p[r[2]] - p[r[0]]).dot(q - p[r[0]]));
}

}  // namespace

std::vector<Tri> convexHull(const std::vector<Vec>& p) {
  if (p.size() < 4) throw InputError("convex hull: fewer than 4 points");
  double extent = 0;
  for (const Vec& q : p) extent = std::max(extent, (q - p[0]).norm());
  const double eps = 1e-12 * extent;

  // A first tetrahedron from far-apart points, so that it is as well shaped as the set allows.
  const std::uint32_t a = farthestFrom(p, fromPoint, {0, 0, 0});
  const std::uint32_t b = farthestFrom(p, fromPoint, {a, 0, 0});
  const std::uint32_t c = farthestFrom(p, fromLine, {a, b, 0});
  const std::uint32_t d = farthestFrom(p, fromPlane, {a, b, c});
  const double volume = (p[b] - p[a]).cross(p[c] - p[a]).dot(p[d] - p[a]);
  if (std::abs(volume) <= eps * extent * extent) throw InputError("convex hull: the points are flat (no volume)");
  std::vector<Tri> faces = volume < 0 ? std::vector<Tri>{{a, b, c}, {a, d, b}, {b, d, c}, {c, d, a}}
                                      : std::vector<Tri>{{a, c, b}, {a, b, d}, {b, c, d}, {c, a, d}};

  for (std::uint32_t i = 0; i < p.size(); ++i) {
    std::vector<Tri> kept, visible;
    for (const Tri& f : faces) (planeDistance(p, f, p[i]) > eps ? visible : kept).push_back(f);
    if (visible.empty()) continue;
    // The horizon: edges of visible faces whose opposite edge is on no visible face.
    std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
    for (const Tri& f : visible)
      for (int k = 0; k < 3; ++k) edges.insert({f[k], f[(k + 1) % 3]});
    for (const auto& e : edges)
      if (!edges.count({e.second, e.first})) kept.push_back({e.first, e.second, i});
    faces = std::move(kept);
  }
  return faces;
}

}  // namespace unidist::odeadapt
