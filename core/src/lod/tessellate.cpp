// The bound (cellDeviation): with the patch in homogeneous form H = (w·S, w) and a triangle's affine map
// A(x, y) = α + β·x + γ·y, S − A = (H_xyz − w·A) / w. The numerator is a polynomial of bidegree (p+1, q+1)
// whose Bernstein coefficients follow from H's and w's by degree elevation (x·B_i^n = (i+1)/(n+1)·B_{i+1}^{n+1}),
// so on each quadrant of the square |S − A| <= max |quadrant coefficient| / min quadrant weight coefficient; a
// triangle takes the three quadrants its half meets.
#include "lod/tessellate.h"

#include "lod/voxel_key.h"
#include "nurbs/patch_tree.h"
#include "unidist/mesh.h"
#include "nurbs/reparametrise.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <set>
#include <unordered_map>

namespace unidist::lod {
namespace {

using Vec3 = Eigen::Vector3d;

/// Coefficients of a bidegree (n, m) Bernstein polynomial, u-major.
template <class T>
struct Grid {
  int n = 0, m = 0;
  std::vector<T> c;
  Grid(int n_, int m_, const T& zero) : n(n_), m(m_), c(static_cast<std::size_t>((n_ + 1) * (m_ + 1)), zero) {}
  T& at(int i, int j) { return c[static_cast<std::size_t>(i * (m + 1) + j)]; }
  const T& at(int i, int j) const { return c[static_cast<std::size_t>(i * (m + 1) + j)]; }
};

/// Degree elevation by one in u (dir 0) or v; with `timesParameter`, the coefficients of x·f (resp. y·f).
template <class T>
Grid<T> elevate(const Grid<T>& f, int dir, bool timesParameter, const T& zero) {
  Grid<T> g(f.n + (dir == 0), f.m + (dir == 1), zero);
  const int top = dir == 0 ? g.n : g.m;
  for (int i = 0; i <= g.n; ++i)
    for (int j = 0; j <= g.m; ++j) {
      const int k = dir == 0 ? i : j;
      const double a = static_cast<double>(k) / top;
      T v = zero;
      if (k > 0) v = v + a * (dir == 0 ? f.at(i - 1, j) : f.at(i, j - 1));
      if (!timesParameter && k < top) v = v + (1 - a) * f.at(i, j);
      g.at(i, j) = v;
    }
  return g;
}

/// The halves [0, ½] and [½, 1] of a grid along u (dir 0) or v, by de Casteljau.
template <class T>
std::pair<Grid<T>, Grid<T>> halve(const Grid<T>& f, int dir) {
  std::pair<Grid<T>, Grid<T>> out{f, f};
  const int top = dir == 0 ? f.n : f.m, other = dir == 0 ? f.m : f.n;
  std::vector<T> work(static_cast<std::size_t>(top + 1), f.c[0]);
  for (int o = 0; o <= other; ++o) {
    const auto at = [&](Grid<T>& g, int k) -> T& { return dir == 0 ? g.at(k, o) : g.at(o, k); };
    for (int k = 0; k <= top; ++k) work[static_cast<std::size_t>(k)] = dir == 0 ? f.at(k, o) : f.at(o, k);
    for (int level = 0; level <= top; ++level) {
      at(out.first, level) = work[0];
      at(out.second, top - level) = work[static_cast<std::size_t>(top - level)];
      for (int k = 0; k < top - level; ++k)
        work[static_cast<std::size_t>(k)] = 0.5 * (work[static_cast<std::size_t>(k)] + work[static_cast<std::size_t>(k + 1)]);
    }
  }
  return out;
}

/// The four quadrants of a grid, index (x ≥ ½) + 2·(y ≥ ½).
template <class T>
std::array<Grid<T>, 4> quadrants(const Grid<T>& f) {
  const auto [left, right] = halve(f, 0);
  const auto [ll, lu] = halve(left, 1);
  const auto [rl, ru] = halve(right, 1);
  return {ll, rl, lu, ru};
}

/// The Bernstein coefficients, at bidegree (p+1, q+1), of w·S (as H's xyz), w, x·w and y·w.
struct ElevatedCell {
  Grid<Vec3> h;
  Grid<double> w, xw, yw;
  std::array<double, 4> wMin{};  // per quadrant
  explicit ElevatedCell(const RationalBezierPatch& cell)
      : h(0, 0, Vec3::Zero()), w(0, 0, 0.0), xw(0, 0, 0.0), yw(0, 0, 0.0) {
    const int n = cell.degreeU, m = cell.degreeV;
    Grid<Vec3> h3(n, m, Vec3::Zero());
    Grid<double> w0(n, m, 0.0);
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= m; ++j) {
        h3.at(i, j) = cell.at(i, j).head<3>();
        w0.at(i, j) = cell.at(i, j)[3];
      }
    const Vec3 zero3 = Vec3::Zero();
    h = elevate(elevate(h3, 0, false, zero3), 1, false, zero3);
    w = elevate(elevate(w0, 0, false, 0.0), 1, false, 0.0);
    xw = elevate(elevate(w0, 0, true, 0.0), 1, false, 0.0);
    yw = elevate(elevate(w0, 0, false, 0.0), 1, true, 0.0);
    // w >= its smallest Bernstein coefficient on each quadrant.
    const std::array<Grid<double>, 4> parts = quadrants(w);
    for (std::size_t q = 0; q < 4; ++q) wMin[q] = *std::min_element(parts[q].c.begin(), parts[q].c.end());
  }
};

/// max |E| / min w for one triangle's affine map α + β·x + γ·y, over the quadrants of the square its half
/// meets (`skip`: the quadrant it does not) — a quadrant's coefficients hug the function closer than the square's,
/// and the triangle's map is not extrapolated over the far corner of the other half.
double triangleBound(const ElevatedCell& e, const Vec3& alpha, const Vec3& beta, const Vec3& gamma, int skip) {
  Grid<Vec3> numerator = e.h;
  for (std::size_t k = 0; k < e.h.c.size(); ++k)
    numerator.c[k] = e.h.c[k] - e.w.c[k] * alpha - e.xw.c[k] * beta - e.yw.c[k] * gamma;
  const std::array<Grid<Vec3>, 4> parts = quadrants(numerator);
  double bound = 0;
  for (int q = 0; q < 4; ++q) {
    if (q == skip) continue;
    double worst = 0;
    for (const Vec3& c : parts[static_cast<std::size_t>(q)].c) worst = std::max(worst, c.squaredNorm());
    bound = std::max(bound, std::sqrt(worst) / e.wMin[static_cast<std::size_t>(q)]);
  }
  return bound;
}

/// How much a direction bends: the largest second difference of the Euclidean control points along it.
double bending(const RationalBezierPatch& p, int dir) {
  const int n = p.degreeU, m = p.degreeV;
  double worst = 0;
  if (dir == 0)
    for (int i = 1; i < n; ++i)
      for (int j = 0; j <= m; ++j) worst = std::max(worst, (p.point(i + 1, j) - 2 * p.point(i, j) + p.point(i - 1, j)).norm());
  else
    for (int i = 0; i <= n; ++i)
      for (int j = 1; j < m; ++j) worst = std::max(worst, (p.point(i, j + 1) - 2 * p.point(i, j) + p.point(i, j - 1)).norm());
  return worst;
}

/// The local parameter of a patch stretched by c where the fraction x of its NURBS parameter range lies
/// (the inverse of nurbs::mobius).
double localParameter(double c, double x) {
  if (x <= 0) return 0;
  if (x >= 1) return 1;
  return x / (c * (1 - x) + x);
}

/// Equal parts of every span, endpoints shared: the grid's parameter values along one direction.
std::vector<double> gridValues(const std::vector<std::pair<double, double>>& spans, const std::vector<int>& parts) {
  std::vector<double> values;
  for (std::size_t s = 0; s < spans.size(); ++s)
    for (int k = values.empty() ? 0 : 1; k <= parts[s]; ++k)
      values.push_back(k == parts[s] ? spans[s].second
                                     : spans[s].first + (spans[s].second - spans[s].first) * k / parts[s]);
  return values;
}

struct SurfaceGrid {
  std::vector<double> u, v;
  std::vector<Vec3> points;               // u-major
  std::vector<char> mainDiagonal;         // per cell, u-major
  double deviation = 0;
};

/// Refines one surface's grid until every cell meets `target`; false when the budget runs out.
bool refineSurface(const NurbsModel& model, int surface, double target, std::size_t& budget, SurfaceGrid& out) {
  const NurbsSurface& S = model.surfaces()[static_cast<std::size_t>(surface)];
  std::vector<int> patches;
  for (int k = 0; k < static_cast<int>(model.patches().size()); ++k)
    if (model.patchSurface(k) == surface) patches.push_back(k);
  std::vector<std::pair<double, double>> uSpans, vSpans;
  for (int k : patches) {
    const RationalBezierPatch& p = model.patches()[static_cast<std::size_t>(k)];
    uSpans.emplace_back(p.u0, p.u1);
    vSpans.emplace_back(p.v0, p.v1);
  }
  const auto unique = [](std::vector<std::pair<double, double>>& v) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  };
  unique(uSpans);
  unique(vSpans);
  const auto spanOf = [](const std::vector<std::pair<double, double>>& spans, double a, double b) {
    return static_cast<int>(std::lower_bound(spans.begin(), spans.end(), std::make_pair(a, b)) - spans.begin());
  };
  std::vector<int> ku(uSpans.size(), 1), kv(vSpans.size(), 1);
  for (;;) {
    const double cellsU = std::accumulate(ku.begin(), ku.end(), 0.0), cellsV = std::accumulate(kv.begin(), kv.end(), 0.0);
    if (2 * cellsU * cellsV > static_cast<double>(budget)) return false;
    const std::vector<double> gu = gridValues(uSpans, ku), gv = gridValues(vSpans, kv);
    const std::size_t cells = (gu.size() - 1) * (gv.size() - 1);
    const std::size_t nv = gv.size();
    out.points.assign(gu.size() * nv, Vec3::Zero());
    for (std::size_t i = 0; i < gu.size(); ++i)
      for (std::size_t j = 0; j < nv; ++j) out.points[i * nv + j] = S.evaluate(gu[i], gv[j]);
    out.mainDiagonal.assign(cells, 1);
    std::vector<double> splitU(uSpans.size(), 0), splitV(vSpans.size(), 0);  // worst excess per span, 0: fine
    double worst = 0;
    bool fine = true;
    // Where each span starts in the grid.
    std::vector<std::size_t> uStart(uSpans.size()), vStart(vSpans.size());
    for (std::size_t s = 1; s < uSpans.size(); ++s) uStart[s] = uStart[s - 1] + static_cast<std::size_t>(ku[s - 1]);
    for (std::size_t s = 1; s < vSpans.size(); ++s) vStart[s] = vStart[s - 1] + static_cast<std::size_t>(kv[s - 1]);
    for (int k : patches) {
      const RationalBezierPatch& p = model.patches()[static_cast<std::size_t>(k)];
      const int su = spanOf(uSpans, p.u0, p.u1), sv = spanOf(vSpans, p.v0, p.v1);
      for (int a = 0; a < ku[static_cast<std::size_t>(su)]; ++a)
        for (int b = 0; b < kv[static_cast<std::size_t>(sv)]; ++b) {
          const std::size_t i = uStart[static_cast<std::size_t>(su)] + static_cast<std::size_t>(a);
          const std::size_t j = vStart[static_cast<std::size_t>(sv)] + static_cast<std::size_t>(b);
          const double s0 = localParameter(p.stretchU, (gu[i] - p.u0) / (p.u1 - p.u0));
          const double s1 = localParameter(p.stretchU, (gu[i + 1] - p.u0) / (p.u1 - p.u0));
          const double t0 = localParameter(p.stretchV, (gv[j] - p.v0) / (p.v1 - p.v0));
          const double t1 = localParameter(p.stretchV, (gv[j + 1] - p.v0) / (p.v1 - p.v0));
          const RationalBezierPatch cell = nurbs::subpatch(p, s0, s1, t0, t1);
          // The mesh's corners are the exact evaluations; the bound is about the cell's own corners.
          const int n = cell.degreeU, m = cell.degreeV;
          const double corners = std::max({(cell.point(0, 0) - out.points[i * nv + j]).norm(),
                                           (cell.point(n, 0) - out.points[(i + 1) * nv + j]).norm(),
                                           (cell.point(0, m) - out.points[i * nv + j + 1]).norm(),
                                           (cell.point(n, m) - out.points[(i + 1) * nv + j + 1]).norm()});
          const CellDeviations d = cellDeviations(cell);
          const double dev = std::min(d.mainDiagonal, d.otherDiagonal) + corners;
          out.mainDiagonal[i * (nv - 1) + j] = d.mainDiagonal <= d.otherDiagonal;
          worst = std::max(worst, dev);
          if (!(dev <= target)) {
            fine = false;
            // The error falls about as the square of the cell size: refine by the square root of the excess.
            const double excess = std::isfinite(dev) ? dev / target : 4.0;
            const double bu = bending(cell, 0), bv = bending(cell, 1);
            auto& eu = splitU[static_cast<std::size_t>(su)];
            auto& ev = splitV[static_cast<std::size_t>(sv)];
            if (bu >= 0.5 * bv) eu = std::max(eu, excess);
            if (bv >= 0.5 * bu) ev = std::max(ev, excess);
          }
        }
    }
    if (fine) {
      out.u = gu;
      out.v = gv;
      out.deviation = worst;
      budget -= 2 * cells;
      return true;
    }
    const auto refine = [](int k, double excess) {
      if (excess == 0) return k;
      const double wanted = std::ceil(k * std::sqrt(excess) * 1.05);
      return wanted > 1e7 ? 10'000'000 : std::max(k + 1, static_cast<int>(wanted));
    };
    for (std::size_t s = 0; s < ku.size(); ++s) ku[s] = refine(ku[s], splitU[s]);
    for (std::size_t s = 0; s < kv.size(); ++s) kv[s] = refine(kv[s], splitV[s]);
  }
}

/// Welds points within `tolerance` of an earlier one onto it; returns each point's index among the kept ones
/// and the largest move.
std::vector<std::uint32_t> weld(const std::vector<Vec3>& points, const Vec3& origin, double tolerance,
                                std::vector<Vec3>& kept, double& moved) {
  std::unordered_map<VoxelKey, std::vector<std::uint32_t>, VoxelKeyHash> cells;
  std::vector<std::uint32_t> index(points.size());
  moved = 0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const VoxelKey key = voxelOf(points[k], origin, tolerance);
    std::int64_t found = -1;
    for (int dx = -1; dx <= 1 && found < 0; ++dx)
      for (int dy = -1; dy <= 1 && found < 0; ++dy)
        for (int dz = -1; dz <= 1 && found < 0; ++dz) {
          const auto it = cells.find({key[0] + dx, key[1] + dy, key[2] + dz});
          if (it == cells.end()) continue;
          for (std::uint32_t c : it->second)
            if ((kept[c] - points[k]).norm() <= tolerance) {
              found = c;
              break;
            }
        }
    if (found >= 0) {
      index[k] = static_cast<std::uint32_t>(found);
      moved = std::max(moved, (kept[static_cast<std::size_t>(found)] - points[k]).norm());
    } else {
      index[k] = static_cast<std::uint32_t>(kept.size());
      cells[key].push_back(index[k]);
      kept.push_back(points[k]);
    }
  }
  return index;
}

}  // namespace

CellDeviations cellDeviations(const RationalBezierPatch& cell) {
  const int n = cell.degreeU, m = cell.degreeV;
  const ElevatedCell e(cell);
  const Vec3 p00 = cell.point(0, 0), p10 = cell.point(n, 0), p01 = cell.point(0, m), p11 = cell.point(n, m);
  // The sums round: a few ulps of the coordinates involved.
  const double rounding = 1e-13 * std::max({p00.norm(), p10.norm(), p01.norm(), p11.norm(), 1e-300});
  CellDeviations d;
  // (p00, p10, p11) over y <= x (not the quadrant x < ½ <= y) and (p00, p11, p01) over y >= x
  d.mainDiagonal = std::max(triangleBound(e, p00, p10 - p00, p11 - p10, 2), triangleBound(e, p00, p11 - p01, p01 - p00, 1)) +
                   rounding;
  // (p00, p10, p01) over x + y <= 1 and (p10, p11, p01) over x + y >= 1
  d.otherDiagonal = std::max(triangleBound(e, p00, p10 - p00, p01 - p00, 3),
                             triangleBound(e, p01 + p10 - p11, p11 - p01, p11 - p10, 0)) +
                    rounding;
  return d;
}

Built tessellate(const NurbsModel& model, double maxDeviation) {
  const Aabb box = model.localBounds();
  const double size = box.diagonal();
  const double weldTolerance = 1e-9 * size;  // what a solid's surfaces may miss each other by (unidist/nurbs.h)
  const double target = maxDeviation - weldTolerance;
  if (!(target > 0) || !(size > 0)) return {};
  std::size_t budget = kMaxTessellationTriangles;
  std::vector<Vec3> points;
  std::vector<std::array<std::uint32_t, 4>> quads;  // grid corners (i, j), (i+1, j), (i, j+1), (i+1, j+1)
  std::vector<char> mainDiagonal;
  double deviation = 0;
  for (int s = 0; s < static_cast<int>(model.surfaces().size()); ++s) {
    SurfaceGrid g;
    if (!refineSurface(model, s, target, budget, g)) return {};
    const auto base = static_cast<std::uint32_t>(points.size());
    points.insert(points.end(), g.points.begin(), g.points.end());
    const std::size_t nu = g.u.size(), nv = g.v.size();
    for (std::size_t i = 0; i + 1 < nu; ++i)
      for (std::size_t j = 0; j + 1 < nv; ++j) {
        const auto at = [&](std::size_t a, std::size_t b) { return base + static_cast<std::uint32_t>(a * nv + b); };
        quads.push_back({at(i, j), at(i + 1, j), at(i, j + 1), at(i + 1, j + 1)});
        mainDiagonal.push_back(g.mainDiagonal[i * (nv - 1) + j]);
      }
    deviation = std::max(deviation, g.deviation);
  }
  std::vector<Vec3> vertices;
  double moved = 0;
  const std::vector<std::uint32_t> index = weld(points, box.min, weldTolerance, vertices, moved);
  // Su x Sv is outward for orientation +1: (p00, p10, p11) turns from u toward v.
  const bool flip = model.orientation() < 0;
  std::vector<TriangleMesh::Triangle> triangles, collapsed;
  for (std::size_t c = 0; c < quads.size(); ++c) {
    const auto& q = quads[c];
    const std::uint32_t a = index[q[0]], b = index[q[1]], cc = index[q[2]], d = index[q[3]];
    const std::array<TriangleMesh::Triangle, 2> two =
        mainDiagonal[c] ? std::array<TriangleMesh::Triangle, 2>{{{a, b, d}, {a, d, cc}}}
                        : std::array<TriangleMesh::Triangle, 2>{{{a, b, cc}, {b, d, cc}}};
    for (TriangleMesh::Triangle t : two) {
      if (flip) std::swap(t[1], t[2]);
      (t[0] == t[1] || t[1] == t[2] || t[2] == t[0] ? collapsed : triangles).push_back(t);
    }
  }
  if (triangles.empty()) return {};
  // A collapsed triangle (a pole) is a segment or a point: the union must still hold it, as an edge or a
  // vertex of a kept triangle, for the bound to hold both ways.
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
  std::vector<char> used(vertices.size(), 0);
  for (const auto& t : triangles)
    for (int e = 0; e < 3; ++e) {
      edges.insert(std::minmax(t[static_cast<std::size_t>(e)], t[static_cast<std::size_t>((e + 1) % 3)]));
      used[t[static_cast<std::size_t>(e)]] = 1;
    }
  for (const auto& t : collapsed) {
    const std::uint32_t a = t[0], b = t[0] == t[1] ? t[2] : t[1];
    if (a == b ? !used[a] : !edges.count(std::minmax(a, b))) return {};
  }
  auto mesh = std::make_unique<TriangleMesh>(std::move(vertices), std::move(triangles));
  // Exactly collinear distinct corners (a cell flattened to a curve) would be dropped unseen by the check above.
  if (mesh->stats().droppedZeroArea > 0) return {};
  if (model.isSolid() && !mesh->isSolid()) return {};
  Built b;
  b.deviation = deviation + moved;
  b.model = std::move(mesh);
  return b;
}

}  // namespace unidist::lod
