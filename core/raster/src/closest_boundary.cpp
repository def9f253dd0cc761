// Closest point of the boundary of a union of convex pieces to a point O inside it: rendered on the six cube
// faces around O (boundary_render.cpp), then every reported point is recomputed and proved on the CPU
// (union_geometry.cpp): the best pixels' facets are intersected with their pixel rays in double precision and
// a point just outside each is checked to be outside every piece.
#include "boundary_polish.h"
#include "boundary_render.h"
#include "cube_views.h"
#include "union_geometry.h"
#include "unidist/raster/convex_union.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <string>

namespace unidist::raster {
namespace {
using detail::FacetRef;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr std::size_t kSeenFacets = 24;  // facets around the best pixels that seed the polish

void checkOptions(const BoundaryQueryOptions& options) {
  if (options.resolution < 8 || options.resolution > 4096)
    throw InputError("resolution " + std::to_string(options.resolution) + ": must be 8..4096 pixels per cube face");
  if (options.candidates < 1 || options.candidates > 4096)
    throw InputError("candidates " + std::to_string(options.candidates) + ": must be 1..4096");
}

/// A pixel worth checking: its image distance, where it is, and the facets seen around it (the other side of
/// a crease shows there even when its own pixels are farther).
struct Pixel {
  double distance;
  int view, i, j;
  std::uint32_t id;
  std::vector<std::uint32_t> around;
  bool operator<(const Pixel& other) const { return distance < other.distance; }  // max-heap on distance
};

/// Keeps the `capacity` nearest pixels pushed.
void keepNearest(std::priority_queue<Pixel>& heap, std::size_t capacity, Pixel pixel) {
  if (heap.size() < capacity) {
    heap.push(std::move(pixel));
  } else if (pixel.distance < heap.top().distance) {
    heap.pop();
    heap.push(std::move(pixel));
  }
}

/// Distinct facet ids within `radius` pixels of (i, j).
std::vector<std::uint32_t> idsAround(const std::vector<std::uint32_t>& ids, int n, int i, int j, int radius) {
  std::vector<std::uint32_t> out;
  for (int y = std::max(0, j - radius); y <= std::min(n - 1, j + radius); ++y)
    for (int x = std::max(0, i - radius); x <= std::min(n - 1, i + radius); ++x) {
      const std::uint32_t id = ids[static_cast<std::size_t>(y) * static_cast<std::size_t>(n) + static_cast<std::size_t>(x)];
      if (id != 0 && std::find(out.begin(), out.end(), id) == out.end()) out.push_back(id);
    }
  return out;
}

/// Global facet ids (the colours drawn) ↔ (piece, facet).
class FacetIds {
 public:
  explicit FacetIds(const ConvexUnion& pieces) {
    for (const auto& p : pieces) first_.push_back(total_), total_ += static_cast<std::uint32_t>(p.planes.size());
  }
  std::uint32_t id(int piece, int facet) const { return first_[static_cast<std::size_t>(piece)] + facet + 1; }
  FacetRef facet(std::uint32_t id) const {
    const auto it = std::upper_bound(first_.begin(), first_.end(), id - 1) - 1;
    const int piece = static_cast<int>(it - first_.begin());
    return {piece, static_cast<int>(id - 1 - *it)};
  }

 private:
  std::vector<std::uint32_t> first_;
  std::uint32_t total_ = 0;
};

std::vector<detail::RenderablePiece> prepare(const ConvexUnion& pieces, const Eigen::Vector3d& O,
                                             const std::vector<bool>& contains, const FacetIds& ids) {
  std::vector<detail::RenderablePiece> out(pieces.size());
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const ConvexPolytope& p = pieces[i];
    detail::RenderablePiece& r = out[i];
    r.containsEye = contains[i];
    r.xyz.reserve(p.triangles.size() * 9);
    r.rgba.reserve(p.triangles.size() * 12);
    for (std::size_t t = 0; t < p.triangles.size(); ++t) {
      const std::uint32_t id = ids.id(static_cast<int>(i), p.triangleFacet[t]);
      for (int k : p.triangles[t]) {
        const Eigen::Vector3d v = p.vertices[static_cast<std::size_t>(k)] - O;  // floats near the eye: precise
        r.xyz.insert(r.xyz.end(), {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())});
        for (int b = 0; b < 4; ++b) r.rgba.push_back(static_cast<unsigned char>((id >> (8 * b)) & 0xffu));
        r.box.extend(v);
        r.maxDistance = std::max(r.maxDistance, v.norm());
      }
    }
  }
  return out;
}

using Best = detail::BestPoint;

/// The point where the pixel ray u meets the facet's plane, if proved on the boundary.
bool provePixel(const detail::UnionGeometry& g, const Eigen::Vector3d& O, const Eigen::Vector3d& u, FacetRef f,
                Best& best) {
  const Eigen::Vector4d& plane = g.pieces()[static_cast<std::size_t>(f.piece)].planes[static_cast<std::size_t>(f.facet)];
  const Eigen::Vector3d n = plane.head<3>();
  const double slope = n.dot(u);
  if (!(slope > 0)) return false;
  const double t = -(n.dot(O) + plane.w()) / slope;
  const Eigen::Vector3d x = O + t * u;
  if (t < 0 || !g.provedOnBoundary(x, f.piece, {n})) return false;
  if (!best.proved || t < best.distance) best = {t, x, f, true};
  return true;
}

}  // namespace

double resolutionErrorBound(double trueDistance, int resolution, double outsideHalfAngle) {
  const double alpha = detail::cubeAngularSpacing(resolution);
  if (!(alpha < outsideHalfAngle)) return kInf;
  return trueDistance * (std::sin(outsideHalfAngle) / std::sin(outsideHalfAngle - alpha) - 1.0);
}

BoundaryPoint closestBoundaryPoint(OffscreenContext& context, const ConvexUnion& pieces, const Eigen::Vector3d& O,
                                   const BoundaryQueryOptions& options) {
  checkOptions(options);
  if (!O.allFinite()) throw InputError("closest boundary point: the query point has a non-finite coordinate");
  detail::validateUnion(pieces, "union");
  const detail::UnionGeometry g(pieces, O);

  BoundaryPoint result;
  result.point = O;
  result.angularSpacing = detail::cubeAngularSpacing(options.resolution);
  result.pushOut = g.pushOut();
  // The pieces holding O: beyond rounding (the deepest gives the lower bound: a ball of its depth lies in the
  // union), or with O on their boundary (O on a face shared by touching pieces is still inside the union).
  std::vector<bool> contains(pieces.size(), false);
  double deepest = 0, touchingSize = 0;
  Eigen::Vector3d deepestExit = Eigen::Vector3d::UnitZ();
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const double depth = -g.planeMax(static_cast<int>(i), O);
    if (depth < -g.margin()) continue;
    contains[i] = true;
    touchingSize = std::max(touchingSize, g.box(static_cast<int>(i)).diagonal());
    if (depth > deepest) {
      deepest = depth;
      for (const auto& plane : pieces[i].planes)
        if (plane.head<3>().dot(O) + plane.w() >= -depth) deepestExit = plane.head<3>();
    }
  }
  if (touchingSize == 0) return result;  // outside every piece: distance 0
  const bool strictlyInside = deepest > g.margin();
  result.lowerBound = strictlyInside ? deepest - g.margin() : 0.0;

  const FacetIds ids(pieces);
  const std::vector<detail::RenderablePiece> renderable = prepare(pieces, O, contains, ids);
  std::vector<int> order;  // the other pieces, nearest first
  for (std::size_t i = 0; i < pieces.size(); ++i)
    if (!contains[i]) order.push_back(static_cast<int>(i));
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return renderable[static_cast<std::size_t>(a)].box.distanceTo(Eigen::Vector3d::Zero()) <
           renderable[static_cast<std::size_t>(b)].box.distanceTo(Eigen::Vector3d::Zero());
  });
  // Every boundary point is at least `deepest` from O, so at eye depth >= deepest/√3 in its view. With O on
  // piece boundaries only, nothing is known: a small fraction of the pieces' size (nearer fragments are clamped
  // to the near plane, not clipped, and the CPU proof recomputes every reported distance anyway).
  const double nearPlane = 0.99 * std::max(deepest, 1e-3 * touchingSize) / std::sqrt(3.0);
  const int n = options.resolution;
  const auto views = detail::cubeViews();
  std::priority_queue<Pixel> bestPixels;  // the `candidates` nearest pixels over all views
  const std::size_t capacity = static_cast<std::size_t>(options.candidates);
  bool uncovered = false;
  {
    detail::BoundaryRenderer renderer(context, n);
    for (int v = 0; v < 6; ++v) {
      const detail::ViewImage image =
          renderer.render(views[static_cast<std::size_t>(v)], renderable, order, nearPlane, static_cast<int>(order.size()) + 1);
      result.passes += image.passes;
      result.piecesRendered += image.rendered;
      result.piecesCulled += image.culled;
      std::priority_queue<Pixel> viewBest;
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const std::size_t p = static_cast<std::size_t>(j) * static_cast<std::size_t>(n) + static_cast<std::size_t>(i);
          if (image.ids[p] == 0) {
            uncovered = true;  // a ray leaving at once: O is on the boundary
            continue;
          }
          keepNearest(viewBest, capacity, {image.distance(views[static_cast<std::size_t>(v)], n, i, j, image.depth[p]), v,
                                           i, j, image.ids[p], {}});
        }
      for (; !viewBest.empty(); viewBest.pop()) {
        Pixel pixel = viewBest.top();
        pixel.around = idsAround(image.ids, n, pixel.i, pixel.j, 3);
        keepNearest(bestPixels, capacity, std::move(pixel));
      }
    }
  }
  if (!strictlyInside && uncovered) return result;  // O on the union's boundary: distance 0
  result.inside = true;
  std::vector<Pixel> pixels;
  for (; !bestPixels.empty(); bestPixels.pop()) pixels.push_back(bestPixels.top());
  std::reverse(pixels.begin(), pixels.end());  // nearest first

  // Prove the pixels on the CPU; the facets they show seed the polish.
  Best best;
  best.distance = kInf;
  std::vector<FacetRef> seen;  // facets around the best proved pixels, nearest first
  for (const Pixel& px : pixels) {
    const Eigen::Vector3d u = views[static_cast<std::size_t>(px.view)].pixelRay(n, px.i, px.j).normalized();
    if (!provePixel(g, O, u, ids.facet(px.id), best)) continue;
    for (std::uint32_t id : px.around) {
      const FacetRef f = ids.facet(id);
      if (seen.size() < kSeenFacets &&
          std::none_of(seen.begin(), seen.end(), [&](FacetRef s) { return s.piece == f.piece && s.facet == f.facet; }))
        seen.push_back(f);
    }
  }
  if (!best.proved) {
    // No pixel survived the proof (coincidences the image resolved differently): walk the best ray exactly.
    const Eigen::Vector3d u =
        pixels.empty() ? deepestExit : views[static_cast<std::size_t>(pixels[0].view)].pixelRay(n, pixels[0].i, pixels[0].j).normalized();
    const detail::UnionGeometry::Exit exit = g.walkRay(O, u);
    best = {exit.t, O + exit.t * u, exit.facet, exit.proved};
    if (exit.facet.piece >= 0) seen.push_back(exit.facet);
  }
  result.pixelDistance = best.distance;
  if (options.refine) {
    const double before = best.distance;
    // The pixels' error radius around the best point (a few pixel footprints at its distance).
    detail::polishBoundaryPoint(g, O, seen, 4 * best.distance * std::tan(result.angularSpacing) + g.pushOut(), best);
    result.refined = best.distance < before;
  }

  result.distance = best.distance;
  result.upperBound = best.proved ? best.distance + g.pushOut() : kInf;
  result.point = best.point;
  if (best.distance > 0) result.direction = (best.point - O) / best.distance;
  result.piece = best.facet.piece;
  result.facet = best.facet.facet;
  result.resolutionBound = best.distance * (1.0 / std::cos(result.angularSpacing) - 1.0);
  return result;
}

}  // namespace unidist::raster
