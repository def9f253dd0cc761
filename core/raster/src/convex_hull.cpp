// Convex hulls by qhull's reentrant C library (no global state: each call owns its qhT). qhull merges coplanar
// facets by default in 3-d (C-0), so every facet here is a convex polygon with one plane; we fan-triangulate it.
#include "unidist/raster/convex_union.h"

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

namespace unidist::raster {
namespace {

/// Owns one qhull run: the state, its memory and the stream qhull writes its error messages to.
class QhullRun {
 public:
  QhullRun() : qh_(std::make_unique<qhT>()) {
    errors_ = open_memstream(&errorText_, &errorSize_);
    qh_zero(qh_.get(), errors_);
  }
  ~QhullRun() {
    qh_freeqhull(qh_.get(), !qh_ALL);
    int curlong = 0, totlong = 0;
    qh_memfreeshort(qh_.get(), &curlong, &totlong);
    if (errors_) std::fclose(errors_);
    std::free(errorText_);
  }
  QhullRun(const QhullRun&) = delete;
  QhullRun& operator=(const QhullRun&) = delete;

  /// 0 on success, else qhull's exit code.
  int run(std::vector<double>& coords) {
    char command[] = "qhull";  // qhull takes a mutable string
    return qh_new_qhull(qh_.get(), 3, static_cast<int>(coords.size() / 3), coords.data(), False, command, nullptr,
                        errors_);
  }
  qhT* get() { return qh_.get(); }
  /// qhull's first error line (e.g. "QH6154 qhull precision error: initial simplex is flat").
  std::string firstErrorLine() {
    if (errors_) std::fflush(errors_);
    std::string text = errorText_ ? std::string(errorText_, errorSize_) : std::string();
    const auto start = text.find_first_not_of(" \n");
    if (start == std::string::npos) return "";
    text = text.substr(start);
    return text.substr(0, text.find('\n'));
  }

 private:
  std::unique_ptr<qhT> qh_;
  FILE* errors_ = nullptr;
  char* errorText_ = nullptr;
  std::size_t errorSize_ = 0;
};

}  // namespace

ConvexPolytope convexHull(const std::vector<Eigen::Vector3d>& points) {
  if (points.size() < 4)
    throw InputError("convex hull of " + std::to_string(points.size()) + " points: at least 4 are needed");
  std::vector<double> coords;
  coords.reserve(points.size() * 3);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite())
      throw InputError("convex hull: point " + std::to_string(i) + " has a non-finite coordinate");
    coords.insert(coords.end(), {points[i].x(), points[i].y(), points[i].z()});
  }

  QhullRun qhull;
  if (const int code = qhull.run(coords); code != 0) {
    const std::string why = qhull.firstErrorLine();
    throw InputError("convex hull of " + std::to_string(points.size()) +
                     " points: the points are flat or degenerate (qhull exit code " + std::to_string(code) +
                     (why.empty() ? ")" : "): " + why));
  }
  qhT* qh = qhull.get();

  ConvexPolytope hull;
  std::vector<int> vertexOf(points.size(), -1);
  auto vertexIndex = [&](vertexT* v) {
    const int source = qh_pointid(qh, v->point);
    int& index = vertexOf[static_cast<std::size_t>(source)];
    if (index < 0) {
      index = static_cast<int>(hull.vertices.size());
      hull.vertices.push_back(points[static_cast<std::size_t>(source)]);
      hull.sourceIndex.push_back(source);
    }
    return index;
  };

  facetT* facet = nullptr;
  FORALLfacets {
    const Eigen::Vector3d n(facet->normal[0], facet->normal[1], facet->normal[2]);
    const int facetIndex = static_cast<int>(hull.planes.size());
    hull.planes.emplace_back(n.x(), n.y(), n.z(), facet->offset);
    setT* ordered = qh_facet3vertex(qh, facet);  // the polygon's vertices in cyclic order
    std::vector<int> polygon;
    vertexT* vertex = nullptr;
    vertexT** vertexp = nullptr;
    FOREACHvertex_(ordered) polygon.push_back(vertexIndex(vertex));
    qh_settempfree(qh, &ordered);
    // Orient the cycle counter-clockwise seen from outside (Newell's normal against the facet's).
    Eigen::Vector3d newell = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < polygon.size(); ++i)
      newell += hull.vertices[static_cast<std::size_t>(polygon[i])].cross(
          hull.vertices[static_cast<std::size_t>(polygon[(i + 1) % polygon.size()])]);
    if (newell.dot(n) < 0) std::reverse(polygon.begin(), polygon.end());
    for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
      hull.triangles.push_back({polygon[0], polygon[i], polygon[i + 1]});
      hull.triangleFacet.push_back(facetIndex);
    }
  }
  realT outer = 0, inner = 0;
  qh_outerinner(qh, nullptr, &outer, &inner);
  hull.tolerance = std::max(0.0, static_cast<double>(outer));
  if (hull.planes.size() < 4 || hull.vertices.size() < 4)
    throw InputError("convex hull of " + std::to_string(points.size()) + " points: degenerate (fewer than 4 facets)");
  return hull;
}

}  // namespace unidist::raster
