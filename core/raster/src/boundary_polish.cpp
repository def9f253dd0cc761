#include "boundary_polish.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace unidist::raster::detail {
namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr std::size_t kPolishFacets = 24;  // facets a round combines (≤ 276 creases)
constexpr int kRounds = 8;

/// A stretch [lo, hi] of a line p0 + s·l, and the planes that end it (−1: none).
struct Span {
  double lo = -kInf, hi = kInf;
  FacetRef loBy, hiBy;
};

/// The stretch of the line inside `piece` (planes within `slack` count as holding it); false when empty.
bool clipLine(const UnionGeometry& g, int piece, const Eigen::Vector3d& p0, const Eigen::Vector3d& l, double slack,
              Span& span) {
  const auto& planes = g.pieces()[static_cast<std::size_t>(piece)].planes;
  for (int k = 0; k < static_cast<int>(planes.size()); ++k) {
    const Eigen::Vector4d& plane = planes[static_cast<std::size_t>(k)];
    const double slope = plane.head<3>().dot(l), value = plane.head<3>().dot(p0) + plane.w() - slack;
    if (std::abs(slope) < 1e-14) {
      if (value > 0) return false;
    } else if (slope > 0) {
      if (-value / slope < span.hi) span.hi = -value / slope, span.hiBy = {piece, k};
    } else if (-value / slope > span.lo) {
      span.lo = -value / slope, span.loBy = {piece, k};
    }
  }
  return span.lo <= span.hi;
}

class Polisher {
 public:
  Polisher(const UnionGeometry& g, const Eigen::Vector3d& O, BestPoint& best) : g_(g), O_(O), best_(best) {}

  bool round(const std::vector<FacetRef>& facets) {
    bool improved = false;
    for (std::size_t a = 0; a < facets.size(); ++a) {
      improved |= foot(facets[a]);
      for (std::size_t b = a + 1; b < facets.size(); ++b) improved |= crease(facets[a], facets[b]);
    }
    return improved;
  }

 private:
  const Eigen::Vector4d& plane(FacetRef f) const {
    return g_.pieces()[static_cast<std::size_t>(f.piece)].planes[static_cast<std::size_t>(f.facet)];
  }

  /// Keeps x when closer and proved on the boundary through the facets it lies on.
  bool tryPoint(const Eigen::Vector3d& x, std::initializer_list<FacetRef> on, std::vector<Eigen::Vector3d> pushes = {}) {
    const double d = (x - O_).norm();
    if (!x.allFinite() || !(d < best_.distance)) return false;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (FacetRef f : on)
      if (f.piece >= 0) pushes.push_back(plane(f).head<3>()), sum += plane(f).head<3>();
    if (pushes.size() > 1 && sum.norm() > 1e-9) pushes.insert(pushes.begin(), sum.normalized());
    for (std::size_t i = 0; i + 1 < pushes.size() && i < 3; ++i)  // pairs: the outside of a corner's edges
      for (std::size_t j = i + 1; j < pushes.size() && j < 4; ++j)
        if ((pushes[i] + pushes[j]).norm() > 1e-9) pushes.push_back((pushes[i] + pushes[j]).normalized());
    for (FacetRef f : on)
      if (f.piece >= 0 && g_.provedOnBoundary(x, f.piece, pushes)) {
        best_ = {d, x, f, true};
        return true;
      }
    return false;
  }

  bool foot(FacetRef f) {
    const Eigen::Vector4d& p = plane(f);
    return tryPoint(O_ - (p.head<3>().dot(O_) + p.w()) * p.head<3>(), {f});
  }

  /// The point of the crease of facets f and h closest to O: their planes' line, inside both pieces, outside
  /// every other piece.
  bool crease(FacetRef f, FacetRef h) {
    const Eigen::Vector4d &pf = plane(f), &ph = plane(h);
    const Eigen::Vector3d nf = pf.head<3>(), nh = ph.head<3>();
    const double c = nf.dot(nh);
    if (1 - std::abs(c) < 1e-12) return false;  // parallel: no crease
    // p0 = O + α nf + β nh on both planes is the line's point closest to O; the line runs along l.
    const double rf = -(nf.dot(O_) + pf.w()), rh = -(nh.dot(O_) + ph.w());
    const double det = 1 - c * c;
    const Eigen::Vector3d p0 = O_ + (rf - c * rh) / det * nf + (rh - c * rf) / det * nh;
    const Eigen::Vector3d l = nf.cross(nh).normalized();
    Span on;
    if (!clipLine(g_, f.piece, p0, l, g_.margin(), on) || !clipLine(g_, h.piece, p0, l, g_.margin(), on)) return false;
    // Remove every other piece's stretch; keep the remaining point nearest s = 0 and the plane that ends it.
    std::vector<Span> free{on};
    Aabb reach;
    reach.extend(p0 + std::max(on.lo, -1e300) * l);
    reach.extend(p0 + std::min(on.hi, 1e300) * l);
    for (int k = 0; k < static_cast<int>(g_.pieces().size()) && !free.empty(); ++k) {
      const Aabb& box = g_.box(k);
      if (k == f.piece || k == h.piece || (box.min.array() > reach.max.array()).any() ||
          (reach.min.array() > box.max.array()).any())
        continue;
      Span inside;
      if (!clipLine(g_, k, p0, l, 0.0, inside)) continue;
      std::vector<Span> left;
      for (const Span& s : free) {
        if (inside.hi <= s.lo || inside.lo >= s.hi) {
          left.push_back(s);
          continue;
        }
        if (inside.lo > s.lo) left.push_back({s.lo, inside.lo, s.loBy, inside.loBy});
        if (inside.hi < s.hi) left.push_back({inside.hi, s.hi, inside.hiBy, s.hiBy});
      }
      free.swap(left);
    }
    bool improved = false;
    // At a stretch's end the crease goes on, free, one way: the outside lies in the wedge between the facets,
    // leaning that way.
    const Eigen::Vector3d bisector = (nf + nh).norm() > 1e-9 ? Eigen::Vector3d((nf + nh).normalized()) : nf;
    for (const Span& s : free) {
      const double t = std::clamp(0.0, s.lo, s.hi);
      const double along = t == s.lo ? 1.0 : (t == s.hi ? -1.0 : 0.0);
      const FacetRef end = along > 0 ? s.loBy : (along < 0 ? s.hiBy : FacetRef{});
      improved |= tryPoint(p0 + t * l, {f, h, end},
                           {(bisector + along * l).normalized(), (bisector + 0.25 * along * l).normalized()});
    }
    return improved;
  }

  const UnionGeometry& g_;
  const Eigen::Vector3d& O_;
  BestPoint& best_;
};

}  // namespace

std::vector<FacetRef> facetsNear(const UnionGeometry& g, const Eigen::Vector3d& x, double radius, std::size_t limit) {
  std::vector<std::pair<double, FacetRef>> near;
  for (int i = 0; i < static_cast<int>(g.pieces().size()); ++i) {
    if (g.box(i).distanceTo(x) > radius || g.planeMax(i, x) > radius) continue;
    const auto& planes = g.pieces()[static_cast<std::size_t>(i)].planes;
    for (int k = 0; k < static_cast<int>(planes.size()); ++k) {
      const Eigen::Vector4d& p = planes[static_cast<std::size_t>(k)];
      const double offset = std::abs(p.head<3>().dot(x) + p.w());
      if (offset <= radius) near.push_back({offset, {i, k}});
    }
  }
  std::sort(near.begin(), near.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<FacetRef> out;
  for (std::size_t k = 0; k < near.size() && out.size() < limit; ++k) out.push_back(near[k].second);
  return out;
}

bool polishBoundaryPoint(const UnionGeometry& g, const Eigen::Vector3d& O, std::vector<FacetRef> facets, double radius,
                         BestPoint& best) {
  Polisher polisher(g, O, best);
  const double before = best.distance;
  for (int round = 0; round < kRounds; ++round) {
    if (facets.size() > kPolishFacets) facets.resize(kPolishFacets);
    const bool improved = polisher.round(facets);
    if (!improved && round > 0) break;
    facets = facetsNear(g, best.point, radius, kPolishFacets);
  }
  return best.distance < before;
}

}  // namespace unidist::raster::detail
