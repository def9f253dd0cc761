// Signed distance of two unions of convex pieces (Kim et al.'s penetration depth pipeline): separated pieces by
// GJK over piece pairs; overlapping ones through the union of the pairwise Minkowski sums A_i ⊕ (−B_j), whose
// boundary point closest to the origin is the translation that separates B from A.
#include "convex/gjk.h"
#include "union_geometry.h"
#include "unidist/raster/convex_union.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

namespace unidist::raster {
namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEps = std::numeric_limits<double>::epsilon();
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

/// A union's pieces moved into the world: their vertices and boxes.
struct PosedUnion {
  std::vector<std::vector<Eigen::Vector3d>> vertices;
  std::vector<Aabb> boxes;
  Aabb box;
  double magnitude = 0;  ///< largest |coordinate|

  PosedUnion(const ConvexUnion& pieces, const Eigen::Isometry3d& X) {
    for (const ConvexPolytope& p : pieces) {
      vertices.emplace_back();
      boxes.emplace_back();
      for (const auto& v : p.vertices) {
        vertices.back().push_back(X * v);
        boxes.back().extend(vertices.back().back());
        magnitude = std::max(magnitude, vertices.back().back().cwiseAbs().maxCoeff());
      }
      box.extend(boxes.back().min);
      box.extend(boxes.back().max);
    }
  }
  double support(const Eigen::Vector3d& u) const {
    double h = -kInf;
    for (const auto& piece : vertices)
      for (const auto& v : piece) h = std::max(h, u.dot(v));
    return h;
  }
};

/// Distance between two boxes (0 when they overlap): a lower bound on the distance of what they hold.
double boxGap(const Aabb& a, const Aabb& b) {
  const Eigen::Vector3d gap = (a.min - b.max).cwiseMax(b.min - a.max).cwiseMax(0.0);
  return gap.norm();
}

/// A proved upper bound on the penetration depth: moving B by h_A(u) + h_B(−u) along u separates the unions'
/// hulls, so it separates the unions. The best of the 26 cube directions (faces, edges, corners).
double depthUpperBySupports(const PosedUnion& A, const PosedUnion& B, Eigen::Vector3d& direction) {
  double best = kInf;
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z) {
        if (x == 0 && y == 0 && z == 0) continue;
        const Eigen::Vector3d u = Eigen::Vector3d(x, y, z).normalized();
        const double s = A.support(u) + B.support(-u);
        if (s < best) best = s, direction = u;
      }
  return best + 16 * kEps * (A.magnitude + B.magnitude);  // the dot products' rounding
}

/// pointA in A_i and pointB in B_j with pointA − pointB = x, from the Minkowski facet holding x: each hull vertex
/// of the sum is a difference of a vertex of A_i and one of B_j, and x's barycentric weights in the facet's
/// triangle carry over to both.
void witnesses(const ConvexPolytope& sum, int facet, const Eigen::Vector3d& x, const std::vector<Eigen::Vector3d>& ai,
               const std::vector<Eigen::Vector3d>& bj, Eigen::Vector3d& pointA, Eigen::Vector3d& pointB) {
  double bestWorst = -kInf;
  Eigen::Vector3d weights(1, 0, 0);
  const std::array<int, 3>* chosen = nullptr;
  for (std::size_t t = 0; t < sum.triangles.size(); ++t) {
    if (sum.triangleFacet[t] != facet) continue;
    const auto& tri = sum.triangles[t];
    const Eigen::Vector3d p0 = sum.vertices[static_cast<std::size_t>(tri[0])];
    const Eigen::Vector3d e1 = sum.vertices[static_cast<std::size_t>(tri[1])] - p0,
                          e2 = sum.vertices[static_cast<std::size_t>(tri[2])] - p0, r = x - p0;
    const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2), det = d11 * d22 - d12 * d12;
    if (!(det > 0)) continue;
    const double v = (d22 * e1.dot(r) - d12 * e2.dot(r)) / det, w = (d11 * e2.dot(r) - d12 * e1.dot(r)) / det;
    const Eigen::Vector3d lambda(1 - v - w, v, w);
    if (lambda.minCoeff() > bestWorst) bestWorst = lambda.minCoeff(), weights = lambda, chosen = &tri;
  }
  if (!chosen) {  // cannot happen for a valid hull; keep the points defined
    pointA = ai[0];
    pointB = ai[0] - x;
    return;
  }
  weights = weights.cwiseMax(0.0);
  weights /= weights.sum();
  pointA.setZero();
  pointB.setZero();
  const std::size_t nb = bj.size();
  for (int k = 0; k < 3; ++k) {
    const std::size_t source = static_cast<std::size_t>(sum.sourceIndex[static_cast<std::size_t>((*chosen)[k])]);
    pointA += weights[k] * ai[source / nb];
    pointB += weights[k] * bj[source % nb];
  }
}

/// B moved by t overlaps no piece of A: every pair whose boxes meet is proved apart by GJK.
bool provedFree(const PosedUnion& A, const PosedUnion& B, const Eigen::Vector3d& t, double tolerance, int maxIterations) {
  for (std::size_t j = 0; j < B.vertices.size(); ++j) {
    Aabb moved = B.boxes[j];
    moved.min += t;
    moved.max += t;
    std::vector<Eigen::Vector3d> bj;
    for (std::size_t i = 0; i < A.vertices.size(); ++i) {
      if (boxGap(A.boxes[i], moved) > 0) continue;
      if (bj.empty())
        for (const auto& v : B.vertices[j]) bj.push_back(v + t);
      const auto d = unidist::detail::convexDistance(unidist::detail::supportOfPointSet(A.vertices[i]),
                                                     unidist::detail::supportOfPointSet(bj), tolerance, maxIterations,
                                                     false);
      if (!(d.lowerBound > 0)) return false;
    }
  }
  return true;
}

/// A translation of B proved to free it from A: an upper bound on the depth, with the points it moves apart.
struct FreeTranslation {
  double depth = kInf;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ(), pointA = Eigen::Vector3d::Zero();
  bool fromPair = false;  ///< a pair's escape (else only the supporting-plane bound)
};

/// A tight proved upper bound on the depth (it decides which Minkowski sums are built): each overlapping pair's
/// own escape (EPA), lengthened until B moved that far is proved free of A. Where one pair decides the depth,
/// its escape is free at once and the answer is exact.
FreeTranslation freeTranslation(const PosedUnion& A, const PosedUnion& B, const std::vector<std::pair<int, int>>& pairs,
                                double tolerance, int maxIterations, double bound) {
  FreeTranslation best;
  best.depth = bound;
  for (const auto& [i, j] : pairs) {
    const auto d = unidist::detail::convexDistance(
        unidist::detail::supportOfPointSet(A.vertices[static_cast<std::size_t>(i)]),
        unidist::detail::supportOfPointSet(B.vertices[static_cast<std::size_t>(j)]), tolerance, maxIterations, true);
    const double depth = std::max(-d.distance, 0.0);
    for (double scale = 1.0; scale * depth + tolerance < best.depth; scale *= 1.5) {
      const double s = scale * depth + tolerance;
      if (!provedFree(A, B, s * d.normal, tolerance, maxIterations)) continue;
      best = {s, d.normal, d.pointA, true};
      break;
    }
  }
  return best;
}

void checkOptions(const UnionDistanceOptions& options, const Eigen::Isometry3d& X_WA, const Eigen::Isometry3d& X_WB) {
  if (options.resolution < 8 || options.resolution > 4096)
    throw InputError("resolution " + std::to_string(options.resolution) + ": must be 8..4096 pixels per cube face");
  if (std::isnan(options.tolerance) || std::isinf(options.tolerance))
    throw InputError("tolerance must be a finite number");
  if (options.maxIterations < 1) throw InputError("maxIterations must be >= 1");
  if (!X_WA.matrix().allFinite()) throw InputError("pose of A has a non-finite entry");
  if (!X_WB.matrix().allFinite()) throw InputError("pose of B has a non-finite entry");
}

}  // namespace

UnionDistanceReport unionDistanceReport(OffscreenContext& context, const ConvexUnion& a, const Eigen::Isometry3d& X_WA,
                                        const ConvexUnion& b, const Eigen::Isometry3d& X_WB,
                                        const UnionDistanceOptions& options) {
  checkOptions(options, X_WA, X_WB);
  detail::validateUnion(a, "union A");
  detail::validateUnion(b, "union B");
  const PosedUnion A(a, X_WA), B(b, X_WB);
  const double tolerance =
      options.tolerance >= 0 ? options.tolerance : 1e-9 * std::max(A.box.diagonal(), B.box.diagonal());

  UnionDistanceReport report;
  report.piecePairs = static_cast<int>(a.size() * b.size());
  struct Pair {
    int i, j;
    double gap;  ///< box distance: a lower bound on the pair's distance
  };
  std::vector<Pair> pairs;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j)
      pairs.push_back({static_cast<int>(i), static_cast<int>(j), boxGap(A.boxes[i], B.boxes[j])});
  std::sort(pairs.begin(), pairs.end(), [](const Pair& p, const Pair& q) { return p.gap < q.gap; });

  // GJK (no EPA) over the pairs, nearest boxes first, until the boxes are farther than the best pair.
  DistanceResult& r = report.result;
  r.method = "convex pieces";
  double lower = kInf;
  bool mayOverlap = false;
  std::vector<std::pair<int, int>> touching;  // pairs not proved apart
  for (const Pair& p : pairs) {
    if (p.gap > r.upperBound) {
      lower = std::min(lower, p.gap);
      break;  // sorted: every later pair is at least this far
    }
    const auto& ai = A.vertices[static_cast<std::size_t>(p.i)];
    const auto& bj = B.vertices[static_cast<std::size_t>(p.j)];
    const unidist::detail::ConvexDistance d = unidist::detail::convexDistance(
        unidist::detail::supportOfPointSet(ai), unidist::detail::supportOfPointSet(bj),
                                                            tolerance, options.maxIterations, false);
    r.iterations += d.iterations;
    lower = std::min(lower, d.lowerBound);
    if (!(d.lowerBound > 0)) mayOverlap = true, touching.emplace_back(p.i, p.j);
    if (d.upperBound < r.upperBound || (d.upperBound == r.upperBound && d.distance < r.distance)) {
      r.distance = d.distance;
      r.pointA = d.pointA;
      r.pointB = d.pointB;
      r.normal = d.normal;
      r.upperBound = d.upperBound;
    }
  }
  r.lowerBound = lower;
  if (!mayOverlap) {  // separated: the minimum over pairs, as exact as GJK
    r.status = r.upperBound - r.lowerBound <= tolerance ? Status::Certified : Status::Bounded;
    return report;
  }

  // Overlapping or touching. Only sums within the proved depth bound of the origin can shape the boundary there.
  Eigen::Vector3d supportDirection = Eigen::Vector3d::UnitZ();
  const FreeTranslation escape =
      freeTranslation(A, B, touching, tolerance, options.maxIterations, depthUpperBySupports(A, B, supportDirection));
  const double depthUpper = escape.depth;
  const auto sumsStart = Clock::now();
  ConvexUnion sums;
  std::vector<Pair> sumPairs;
  for (const Pair& p : pairs) {
    if (p.gap > std::max(depthUpper, 0.0)) break;
    const auto& ai = A.vertices[static_cast<std::size_t>(p.i)];
    const auto& bj = B.vertices[static_cast<std::size_t>(p.j)];
    std::vector<Eigen::Vector3d> differences;
    differences.reserve(ai.size() * bj.size());
    for (const auto& va : ai)
      for (const auto& vb : bj) differences.push_back(va - vb);
    sums.push_back(convexHull(differences));
    sumPairs.push_back(p);
  }
  report.sums = static_cast<int>(sums.size());
  report.sumsSeconds = secondsSince(sumsStart);

  const auto queryStart = Clock::now();
  BoundaryQueryOptions query;
  query.resolution = options.resolution;
  query.refine = options.refine;
  const BoundaryPoint bp = closestBoundaryPoint(context, sums, Eigen::Vector3d::Zero(), query);
  report.querySeconds = secondsSince(queryStart);
  report.boundary = bp;
  {
    const detail::UnionGeometry g(sums, Eigen::Vector3d::Zero());
    for (std::size_t s = 0; s < sums.size(); ++s)
      if (g.planeMax(static_cast<int>(s), Eigen::Vector3d::Zero()) < -g.margin()) ++report.overlappingPairs;
  }
  if (!bp.inside) {  // touching: no pair's interiors overlap, so neither do the unions'
    r.lowerBound = std::min(r.lowerBound, -depthUpper);
    r.status = r.upperBound - r.lowerBound <= tolerance ? Status::Certified : Status::Bounded;
    return report;
  }

  // B moves by x = bp.point to separate: distance −|x|, normal x/|x|, pointA − pointB = x.
  r.method = "raster";
  r.iterations = bp.passes;
  r.lowerBound = -std::min(bp.upperBound, depthUpper);
  r.upperBound = -bp.lowerBound;
  if (bp.distance <= depthUpper) {
    const Pair& p = sumPairs[static_cast<std::size_t>(bp.piece)];
    r.distance = -bp.distance;
    r.normal = bp.direction;
    Eigen::Vector3d pointB;
    witnesses(sums[static_cast<std::size_t>(bp.piece)], bp.facet, bp.point, A.vertices[static_cast<std::size_t>(p.i)],
              B.vertices[static_cast<std::size_t>(p.j)], r.pointA, pointB);
  } else if (escape.fromPair) {
    // A pair's own escape, proved free, beats the image (exact where that pair decides the depth).
    r.distance = -depthUpper;
    r.normal = escape.normal;
    r.pointA = escape.pointA;
  } else {  // a coarse image did worse than the supporting planes: report their translation
    r.distance = -depthUpper;
    r.normal = supportDirection;
    double h = -kInf;
    for (const auto& piece : A.vertices)
      for (const auto& v : piece)
        if (supportDirection.dot(v) > h) h = supportDirection.dot(v), r.pointA = v;
  }
  r.pointB = r.pointA + r.distance * r.normal;
  r.status = r.upperBound - r.lowerBound <= tolerance ? Status::Certified : Status::Bounded;
  return report;
}

DistanceResult unionDistance(OffscreenContext& context, const ConvexUnion& a, const Eigen::Isometry3d& X_WA,
                             const ConvexUnion& b, const Eigen::Isometry3d& X_WB, const UnionDistanceOptions& options) {
  return unionDistanceReport(context, a, X_WA, b, X_WB, options).result;
}

}  // namespace unidist::raster
