// Mesh hierarchy benchmark: build time, memory per triangle and point-query time for tori of ~1k, ~10k and
// ~100k triangles, and which bounding volume prunes point queries best (the AABB, the ball, or both).
//
//   unidist_bench_mesh_build [queries=20000]
//
// Prints CSV: triangles, build_ms (median of 7 builds), bvh_bytes_per_triangle, model_bytes_per_triangle,
// depth, then the median point-query time in µs for points near the surface (within 2 % of the size) and far
// from it (uniform in [-3, 3]³, the torus being ~2 across), with each pruning volume (a copy of the library's
// traversal), then TriangleMesh::closestPoint itself (near, far) and inside() (winding number; the first
// call builds its data outside the timing). The three traversals' answers are compared: a fast wrong answer
// fails the run.
#include "core/mesh_fixtures.h"
#include "mesh/bvh.h"
#include "mesh/point_triangle.h"
#include "unidist/mesh.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

namespace {

using meshfix::Vec;
using unidist::TriangleMesh;
using unidist::mesh::BvhNode;
using unidist::mesh::MeshBvh;

enum class Prune { Box, Ball, Both };

// The library's traversal (mesh/bvh.h nearestSearch) with the pruning volume as a choice.
double nearest(const TriangleMesh& m, const MeshBvh& b, const Vec& q, Prune prune) {
  const auto lower = [&](std::uint32_t i) {
    double box = 0, ball = 0;
    if (prune != Prune::Ball) box = b.tree.nodes[i].squaredDistance(q);
    if (prune != Prune::Box) {
      const double d = std::max(0.0, (q - b.spheres[i].center).norm() - b.spheres[i].radius);
      ball = d * d;
    }
    return std::max(box, ball);
  };
  double best = std::numeric_limits<double>::infinity();
  struct Entry {
    std::uint32_t node;
    double d;
  };
  Entry stack[128];
  int top = 0;
  std::uint32_t current = 0;
  for (;;) {
    const BvhNode& n = b.tree.nodes[current];
    if (n.leaf()) {
      for (std::uint32_t s = n.first; s < n.first + n.count; ++s) {
        const std::uint32_t t = b.tree.order[s];
        const auto& tri = m.triangles()[t];
        const Vec& a = m.vertices()[tri[0]];
        const double h = m.faceNormal(static_cast<int>(t)).dot(q - a);
        if (h * h >= best) continue;
        const auto r = unidist::mesh::closestOnTriangle(q, a, m.vertices()[tri[1]], m.vertices()[tri[2]],
                                                        m.faceNormal(static_cast<int>(t)));
        best = std::min(best, r.squaredDistance);
      }
    } else {
      std::uint32_t near = n.first, far = n.first + 1;
      double dn = lower(near), df = lower(far);
      if (df < dn) std::swap(near, far), std::swap(dn, df);
      if (dn < best) {
        if (df < best) stack[top++] = {far, df};
        current = near;
        continue;
      }
    }
    bool found = false;
    while (top > 0) {
      const Entry e = stack[--top];
      if (e.d < best) {
        current = e.node;
        found = true;
        break;
      }
    }
    if (!found) return std::sqrt(best);
  }
}

template <class F>
double medianMicros(int reps, F&& f) {
  std::vector<double> t;
  for (int i = 0; i < reps; ++i) {
    const auto s = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - s).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const int queries = argc > 1 ? std::atoi(argv[1]) : 20000;
  std::printf("triangles,build_ms,bvh_bytes_per_triangle,model_bytes_per_triangle,depth,"
              "near_us_box,near_us_ball,near_us_both,far_us_box,far_us_ball,far_us_both,model_near_us,model_far_us,"
              "inside_us\n");
  for (int n : {22, 71, 224}) {  // torus(2n × n/2): ~1k, ~10k, ~100k triangles
    const meshfix::Soup soup = meshfix::torus(0.8, 0.25, 2 * n, n / 2);
    double buildMs = 0, bvhBytes = 0, modelBytes = 0;
    {
      std::vector<double> ms;
      for (int rep = 0; rep < 7; ++rep) {
        const TriangleMesh fresh(soup.vertices, soup.triangles);
        (void)fresh.bvh();
        ms.push_back(fresh.bvhBuildMicroseconds() / 1000);
      }
      std::sort(ms.begin(), ms.end());
      buildMs = ms[3];
    }
    const TriangleMesh m(soup.vertices, soup.triangles);
    const double tris = static_cast<double>(m.triangles().size());
    modelBytes = static_cast<double>(m.memoryBytes()) / tris;
    const MeshBvh& b = m.bvh();
    bvhBytes = static_cast<double>(m.memoryBytes()) / tris - modelBytes;

    std::mt19937_64 rng(1);
    std::vector<Vec> nearPts = meshfix::queryPoints(soup, 2 * queries, 0.02, 0.0, rng), near, far;
    for (std::size_t i = 0; i < nearPts.size(); i += 2) near.push_back(nearPts[i]);
    std::uniform_real_distribution<double> u(-3, 3);
    for (int i = 0; i < queries; ++i) far.emplace_back(u(rng), u(rng), u(rng));

    double results[2][3];
    for (int set = 0; set < 2; ++set) {
      const std::vector<Vec>& pts = set == 0 ? near : far;
      std::vector<double> answers[3];
      for (int p = 0; p < 3; ++p) {
        const Prune prune = static_cast<Prune>(p);
        answers[p].resize(pts.size());
        results[set][p] = medianMicros(5, [&] {
                            for (std::size_t i = 0; i < pts.size(); ++i) answers[p][i] = nearest(m, b, pts[i], prune);
                          }) /
                          static_cast<double>(pts.size());
      }
      for (std::size_t i = 0; i < pts.size(); ++i)
        if (answers[0][i] != answers[1][i] || answers[0][i] != answers[2][i]) {
          std::fprintf(stderr, "traversals disagree at point %zu\n", i);
          return 1;
        }
    }
    double sink = 0;
    const auto perQuery = [&](const std::vector<Vec>& pts, auto&& f) {
      return medianMicros(5, [&] {
               for (const Vec& q : pts) sink += f(q);
             }) /
             static_cast<double>(pts.size());
    };
    const double modelNear = perQuery(near, [&](const Vec& q) { return m.closestPoint(q).signedDistance; });
    const double modelFar = perQuery(far, [&](const Vec& q) { return m.closestPoint(q).signedDistance; });
    (void)m.inside(near[0]);  // builds the winding data
    const double insideUs = perQuery(near, [&](const Vec& q) { return m.inside(q) ? 1.0 : 0.0; });
    std::printf("%zu,%.2f,%.1f,%.1f,%d,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f\n", m.triangles().size(), buildMs,
                bvhBytes, modelBytes, b.tree.depth, results[0][0], results[0][1], results[0][2], results[1][0],
                results[1][1], results[1][2], modelNear, modelFar, insideUs + 0 * sink);
  }
  return 0;
}
