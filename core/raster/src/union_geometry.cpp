#include "union_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace unidist::raster::detail {
namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEps = std::numeric_limits<double>::epsilon();

std::string pieceName(const char* what, std::size_t i) { return std::string(what) + " piece " + std::to_string(i); }
}  // namespace

void validateUnion(const ConvexUnion& pieces, const char* what) {
  if (pieces.empty()) throw InputError(std::string(what) + ": no convex pieces (empty union)");
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const ConvexPolytope& p = pieces[i];
    if (p.vertices.size() < 4 || p.planes.size() < 4 || p.triangles.size() < 4)
      throw InputError(pieceName(what, i) + ": not a solid polytope (needs >= 4 vertices, facets and triangles)");
    if (p.triangleFacet.size() != p.triangles.size())
      throw InputError(pieceName(what, i) + ": triangleFacet must have one entry per triangle");
    if (!(p.tolerance >= 0) || !std::isfinite(p.tolerance))
      throw InputError(pieceName(what, i) + ": tolerance must be finite and >= 0");
    for (const auto& v : p.vertices)
      if (!v.allFinite()) throw InputError(pieceName(what, i) + ": a vertex has a non-finite coordinate");
    for (const auto& plane : p.planes)
      if (!plane.allFinite() || std::abs(plane.head<3>().norm() - 1.0) > 1e-9)
        throw InputError(pieceName(what, i) + ": a facet plane is not finite with a unit normal");
    const int nv = static_cast<int>(p.vertices.size()), nf = static_cast<int>(p.planes.size());
    for (std::size_t t = 0; t < p.triangles.size(); ++t) {
      for (int k : p.triangles[t])
        if (k < 0 || k >= nv) throw InputError(pieceName(what, i) + ": a triangle indexes a missing vertex");
      if (p.triangleFacet[t] < 0 || p.triangleFacet[t] >= nf)
        throw InputError(pieceName(what, i) + ": a triangle's facet index is out of range");
    }
  }
}

UnionGeometry::UnionGeometry(const ConvexUnion& pieces, const Eigen::Vector3d& origin) : pieces_(pieces) {
  double magnitude = origin.cwiseAbs().maxCoeff(), tolerance = 0;
  Aabb all;
  boxes_.reserve(pieces.size());
  for (const ConvexPolytope& p : pieces) {
    Aabb box;
    for (const auto& v : p.vertices) {
      box.extend(v);
      magnitude = std::max(magnitude, v.cwiseAbs().maxCoeff());
    }
    all.extend(box.min);
    all.extend(box.max);
    boxes_.push_back(box);
    tolerance = std::max(tolerance, p.tolerance);
  }
  // n·p + d rounds at a few ulps of the coordinates; qhull's points may sit its outer distance above a plane.
  margin_ = tolerance + 64 * kEps * std::max(magnitude, 1e-300);
  pushOut_ = std::max(1e-12 * all.diagonal(), 64 * margin_);
}

double UnionGeometry::planeMax(int piece, const Eigen::Vector3d& p) const {
  double worst = -kInf;
  for (const auto& plane : pieces_[static_cast<std::size_t>(piece)].planes)
    worst = std::max(worst, plane.head<3>().dot(p) + plane.w());
  return worst;
}

bool UnionGeometry::provedOutsideAll(const Eigen::Vector3d& p) const {
  for (std::size_t i = 0; i < pieces_.size(); ++i) {
    if (boxes_[i].distanceTo(p) > margin_) continue;  // outside the box: outside the piece
    if (planeMax(static_cast<int>(i), p) <= margin_) return false;
  }
  return true;
}

UnionGeometry::Exit UnionGeometry::walkRay(const Eigen::Vector3d& O, const Eigen::Vector3d& u) const {
  struct Interval {
    double in, out;
    FacetRef leave;
  };
  std::vector<Interval> intervals;
  for (std::size_t i = 0; i < pieces_.size(); ++i) {
    double in = -kInf, out = kInf;
    int leave = -1;
    const auto& planes = pieces_[i].planes;
    for (std::size_t k = 0; k < planes.size() && in <= out; ++k) {
      const double slope = planes[k].head<3>().dot(u), value = planes[k].head<3>().dot(O) + planes[k].w();
      if (slope > 0) {
        const double t = -value / slope;
        if (t < out) out = t, leave = static_cast<int>(k);
      } else if (slope < 0) {
        in = std::max(in, -value / slope);
      } else if (value > 0) {
        in = kInf;  // parallel and outside
      }
    }
    if (in <= out && out > 0 && leave >= 0) intervals.push_back({in, out, {static_cast<int>(i), leave}});
  }
  std::sort(intervals.begin(), intervals.end(), [](const Interval& a, const Interval& b) { return a.in < b.in; });
  // Sweep the covered stretch from O outward; a gap counts only once a point in it is proved outside.
  Exit exit;
  std::size_t next = 0;
  double reach = 0;
  for (;;) {
    while (next < intervals.size() && intervals[next].in <= reach) {
      if (intervals[next].out > reach) reach = intervals[next].out, exit.facet = intervals[next].leave;
      ++next;
    }
    exit.proved = provedOutsideAll(O + (reach + pushOut_) * u);
    if (exit.proved || next >= intervals.size()) break;
    reach += pushOut_;  // undecided: step on (terminates: every piece is bounded)
  }
  exit.t = reach;
  return exit;
}

bool UnionGeometry::provedOnBoundary(const Eigen::Vector3d& x, int piece,
                                     const std::vector<Eigen::Vector3d>& pushDirections) const {
  if (!inPiece(piece, x)) return false;
  for (const auto& w : pushDirections)
    if (provedOutsideAll(x + pushOut_ * w)) return true;
  return false;
}

}  // namespace unidist::raster::detail
