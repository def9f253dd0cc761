// Expanding polytope algorithm (van den Bergen, "Proximity Queries and Penetration Depth Computation on 3D
// Game Objects", GDC 2001) for the penetration depth of two overlapping convex sets.
//
// The polytope P is the convex hull of support points of D = A − B, so P ⊂ D. While P contains the origin,
// the origin's distance to P's closest face is a lower bound on the depth (dist(0, ∂D) >= dist(0, ∂P)), and
// h_D(n) for any unit n is an upper bound. Each step evaluates the support along the closest face's normal and
// adds it to P, replacing the faces it sees (found by a depth-first walk over face adjacency, the horizon
// being the boundary of the walked region). Robustness measures:
//  * the start polytope is the hull of the GJK simplex, the six axis supports and the supports along ± the
//    normal of the largest seed triangle, so it is full-dimensional even when GJK stopped with a point, a
//    segment or a triangle (contact or a flat simplex), and it still contains the GJK simplex (and so the
//    origin whenever GJK found it inside);
//  * an expansion is committed only if the horizon is one simple loop and every new face is non-degenerate
//    and faces away from a fixed interior point; otherwise EPA stops with the bounds it has (never a broken
//    polytope);
//  * a face with the origin on its outer side (GJK stopped just short of enclosing it) is expanded like any
//    other; a support with h_D(n) < 0 proves the sets apart, and the caller keeps the GJK answer.
#include "convex/gjk.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>
#include <cstdio>
#include <cstdlib>
#define DBG(...) do { if (std::getenv("EPADBG")) fprintf(stderr, __VA_ARGS__); } while (0)

namespace unidist::detail {
namespace {

using Eigen::Vector3d;

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Face {
  int v[3] = {0, 0, 0};        // counter-clockwise seen from outside: edge k runs v[k] → v[k+1]
  int adj[3] = {-1, -1, -1};   // face across edge k
  int adjEdge[3] = {0, 0, 0};  // index of that edge in the adjacent face
  Vector3d n = Vector3d::Zero();  // outward unit normal
  double d = 0;                   // n·x on the face: the origin's distance to the plane, > 0 when inside
  int mark = 0;                   // pass in which the face was found visible
  bool alive = true;
};

class Polytope {
 public:
  explicit Polytope(double eps) : eps_(eps) {}

  std::vector<SupportPoint> verts;
  std::vector<Face> faces;

  // Tetrahedron i0..i3 (any orientation); false if it is flat to working precision.
  bool init(int i0, int i1, int i2, int i3) {
    const Vector3d& p0 = verts[i0].w;
    if ((verts[i1].w - p0).cross(verts[i2].w - p0).dot(verts[i3].w - p0) > 0) std::swap(i1, i2);
    interior_ = 0.25 * (verts[i0].w + verts[i1].w + verts[i2].w + verts[i3].w);
    const int tri[4][3] = {{i0, i1, i2}, {i0, i3, i1}, {i1, i3, i2}, {i2, i3, i0}};
    for (const auto& t : tri) {
      Face f;
      if (!makeFace(t[0], t[1], t[2], f)) return false;
      faces.push_back(f);
    }
    for (int f = 0; f < 4; ++f)
      for (int k = 0; k < 3; ++k)
        for (int g = 0; g < 4; ++g)
          for (int m = 0; m < 3; ++m)
            if (faces[f].v[k] == faces[g].v[(m + 1) % 3] && faces[f].v[(k + 1) % 3] == faces[g].v[m]) {
              faces[f].adj[k] = g;
              faces[f].adjEdge[k] = m;
            }
    for (int f = 0; f < 4; ++f) heap_.emplace(faces[f].d, f);
    return true;
  }

  // The alive face closest to the origin (smallest d, negative when the origin is outside it); −1 if none.
  int closest() {
    while (!heap_.empty() && !faces[heap_.top().second].alive) heap_.pop();
    return heap_.empty() ? -1 : heap_.top().second;
  }

  // The face that sees p farthest above its plane, and that height.
  int mostVisible(const Vector3d& p, double& height) const {
    int best = -1;
    height = -kInf;
    for (int f = 0; f < static_cast<int>(faces.size()); ++f) {
      if (!faces[f].alive) continue;
      const double h = faces[f].n.dot(p) - faces[f].d;
      if (h > height) {
        height = h;
        best = f;
      }
    }
    return best;
  }

  // Adds vertex vi, which face f0 sees, to the hull. Returns false, changing nothing, when the update would
  // not give a valid closed polytope.
  bool insert(int vi, int f0) {
    const Vector3d p = verts[vi].w;
    ++pass_;
    removed_.clear();
    horizon_.clear();
    faces[f0].mark = pass_;
    removed_.push_back(f0);
    for (int k = 0; k < 3; ++k) silhouette(faces[f0].adj[k], faces[f0].adjEdge[k], p);
    const int m = static_cast<int>(horizon_.size());
    if (m < 3) { DBG("insert fail: m=%d removed=%zu\n", m, removed_.size()); return false; }
    std::vector<Face> fresh(m);
    for (int i = 0; i < m; ++i) {
      const Face& g = faces[horizon_[i].first];
      const int e = horizon_[i].second;
      if (!makeFace(g.v[(e + 1) % 3], g.v[e], vi, fresh[i])) { DBG("insert fail: makeFace m=%d removed=%zu\n", m, removed_.size()); return false; }
      fresh[i].adj[0] = horizon_[i].first;
      fresh[i].adjEdge[0] = e;
    }
    // Link the fan around p: face i's edge v[1] → p meets face j's edge p → v[0] where fresh[j].v[0] == fresh[i].v[1].
    const int base = static_cast<int>(faces.size());
    std::vector<int> next(m, -1);
    for (int i = 0; i < m; ++i) {
      for (int j = 0; j < m; ++j) {
        if (fresh[j].v[0] != fresh[i].v[1]) continue;
        if (next[i] >= 0) { DBG("insert fail: twice\n"); return false; }  // a vertex twice on the horizon: not a simple loop
        next[i] = j;
      }
      if (next[i] < 0) return false;
    }
    int steps = 0;
    for (int i = next[0]; i != 0 && steps <= m; i = next[i]) ++steps;
    if (steps != m - 1) { DBG("insert fail: loops\n"); return false; }  // several loops: the visible region was not a disc
    for (int i = 0; i < m; ++i) {
      fresh[i].adj[1] = base + next[i];
      fresh[i].adjEdge[1] = 2;
      fresh[next[i]].adj[2] = base + i;
      fresh[next[i]].adjEdge[2] = 1;
    }
    for (int f : removed_) faces[f].alive = false;
    for (int i = 0; i < m; ++i) {
      Face& g = faces[horizon_[i].first];
      g.adj[horizon_[i].second] = base + i;
      g.adjEdge[horizon_[i].second] = 0;
      faces.push_back(fresh[i]);
      heap_.emplace(fresh[i].d, base + i);
    }
    return true;
  }

 private:
  bool makeFace(int a, int b, int c, Face& f) const {
    const Vector3d& wa = verts[a].w;
    const Vector3d& wb = verts[b].w;
    const Vector3d& wc = verts[c].w;
    Vector3d n = (wb - wa).cross(wc - wa);
    const double len = n.norm();
    if (!(len > 0)) return false;
    n /= len;
    if (!(n.dot(interior_ - wa) < 0)) return false;  // must face away from the interior
    f.v[0] = a;
    f.v[1] = b;
    f.v[2] = c;
    f.n = n;
    f.d = (n.dot(wa) + n.dot(wb) + n.dot(wc)) / 3;
    return true;
  }

  void silhouette(int fi, int e, const Vector3d& p) {
    Face& f = faces[fi];
    if (f.mark == pass_) return;
    if (f.n.dot(p) - f.d <= eps_) {
      horizon_.emplace_back(fi, e);
      return;
    }
    f.mark = pass_;
    removed_.push_back(fi);
    const int e1 = (e + 1) % 3, e2 = (e + 2) % 3;
    const int a1 = f.adj[e1], k1 = f.adjEdge[e1], a2 = f.adj[e2], k2 = f.adjEdge[e2];
    silhouette(a1, k1, p);
    silhouette(a2, k2, p);
  }

  double eps_;
  Vector3d interior_ = Vector3d::Zero();
  int pass_ = 0;
  std::vector<int> removed_;
  std::vector<std::pair<int, int>> horizon_;
  std::priority_queue<std::pair<double, int>, std::vector<std::pair<double, int>>, std::greater<>> heap_;
};

double maxAbs(const SupportPoint& s) { return std::max(s.a.cwiseAbs().maxCoeff(), s.b.cwiseAbs().maxCoeff()); }

double distanceToLine(const Vector3d& p, const Vector3d& a, const Vector3d& b) {
  const Vector3d d = b - a;
  const double dd = d.squaredNorm();
  if (!(dd > 0)) return (p - a).norm();
  return (p - a - ((p - a).dot(d) / dd) * d).norm();
}

}  // namespace

EpaResult epa(const SupportFn& a, const SupportFn& b, const std::vector<SupportPoint>& seeds, double tolerance,
              int maxIterations, ConvexScale& scale) {
  EpaResult r;
  r.signedLower = -kInf;
  r.depthUpper = kInf;
  for (const SupportPoint& s : seeds) scale.coordMag = std::max(scale.coordMag, maxAbs(s));
  // Support along unit n, recording both bounds it proves.
  auto support = [&](const Vector3d& n) {
    const SupportPoint s = minkowskiSupport(a, b, n);
    scale.coordMag = std::max(scale.coordMag, maxAbs(s));
    const double h = n.dot(s.w);
    r.signedLower = std::max(r.signedLower, -h);
    r.depthUpper = std::min(r.depthUpper, h);
    return s;
  };

  std::vector<SupportPoint> cand;
  for (const SupportPoint& s : seeds) {
    bool dup = false;
    for (const SupportPoint& c : cand) dup = dup || c.w == s.w;
    if (!dup) cand.push_back(s);
  }
  if (cand.empty()) return r;
  const double flat = 64 * scale.roundoff();  // thinner than this, D is flat to working precision

  // Largest triangle of the seeds, greedily: farthest pair, then farthest from their line.
  int i0 = 0, i1 = 0, i2 = 0;
  double best = -1;
  for (int i = 0; i < static_cast<int>(cand.size()); ++i)
    for (int j = i + 1; j < static_cast<int>(cand.size()); ++j) {
      const double d = (cand[i].w - cand[j].w).squaredNorm();
      if (d > best) {
        best = d;
        i0 = i;
        i1 = j;
      }
    }
  if (!(std::sqrt(best) > flat)) return r;
  auto farthestFromLine = [&](double& dist) {
    int k = 0;
    dist = -1;
    for (int i = 0; i < static_cast<int>(cand.size()); ++i) {
      const double d = distanceToLine(cand[i].w, cand[i0].w, cand[i1].w);
      if (d > dist) {
        dist = d;
        k = i;
      }
    }
    return k;
  };
  double lineDist = 0;
  i2 = farthestFromLine(lineDist);
  if (!(lineDist > flat)) {
    // All seeds on a line: add supports in the four directions perpendicular to it.
    const Vector3d u = (cand[i1].w - cand[i0].w).normalized();
    Vector3d p1 = u.unitOrthogonal();
    const Vector3d p2 = u.cross(p1);
    for (const Vector3d& n : {p1, Vector3d(-p1), p2, Vector3d(-p2)}) cand.push_back(support(n));
    i2 = farthestFromLine(lineDist);
    if (!(lineDist > flat)) return r;
  }
  {
    // Supports along ± the triangle's normal make the start polytope full-dimensional.
    const Vector3d n = (cand[i1].w - cand[i0].w).cross(cand[i2].w - cand[i0].w).normalized();
    cand.push_back(support(n));
    cand.push_back(support(-n));
  }
  const Vector3d n012 = (cand[i1].w - cand[i0].w).cross(cand[i2].w - cand[i0].w).normalized();
  int i3 = 0;
  double planeDist = -1;
  for (int i = 0; i < static_cast<int>(cand.size()); ++i) {
    const double d = std::abs(n012.dot(cand[i].w - cand[i0].w));
    if (d > planeDist) {
      planeDist = d;
      i3 = i;
    }
  }
  if (!(planeDist > flat)) return r;

  const double eps = scale.roundoff();
  Polytope poly(eps);
  poly.verts = cand;
  if (!poly.init(i0, i1, i2, i3)) return r;
  for (int i = 0; i < static_cast<int>(cand.size()); ++i) {
    if (i == i0 || i == i1 || i == i2 || i == i3) continue;
    double height = 0;
    const int f = poly.mostVisible(cand[i].w, height);
    if (f >= 0 && height > eps) poly.insert(i, f);  // a failed insertion only leaves the polytope smaller
  }
  r.valid = true;
  DBG("epa start: cand %zu eps %g\n", cand.size(), eps);

  double lastGap = std::numeric_limits<double>::infinity();
  int lastFace = -1;
  for (int it = 0; it < maxIterations; ++it) {
    const int f = poly.closest();
    if (f < 0) break;
    const Vector3d n = poly.faces[f].n;
    const double d = poly.faces[f].d;
    const SupportPoint s = support(n);
    ++r.iterations;
    const double h = n.dot(s.w);
    DBG("epa it %d faces %zu d=%.17g h=%.17g eps=%g\n", it, poly.faces.size(), d, h, eps);
    if (h < -eps) {  // D lies strictly below a plane through the origin: the sets are apart
      r.separated = true;
      break;
    }
    // Stop on the gap of this face (not on the best upper bound so far), so that its witness points are
    // certified too: their depths in A and B sum to at most h − d.
    lastGap = h - d;
    lastFace = f;
    if (d >= -eps && h - d <= tolerance) break;
    if (h - d <= eps) break;  // the face is on D's boundary to working precision: nothing to add
    poly.verts.push_back(s);
    if (!poly.insert(static_cast<int>(poly.verts.size()) - 1, f)) break;
  }

  const int f = poly.closest();
  if (f < 0) {
    r.valid = false;
    return r;
  }
  const Face& face = poly.faces[f];
  r.depth = face.d;
  r.normal = face.n;
  r.originInside = face.d >= -eps;
  // Witness: barycentric coordinates of the origin's foot point q = d·n, carried to A's and B's support points.
  // A facet of a polytope D is triangulated into coplanar faces with equal d, and the heap may name any of them:
  // take, among the faces whose plane holds q, the one that contains q best (largest smallest coordinate).
  // Coordinates from a face that does not contain q would be clamped, moving the points sideways off the sets.
  const Vector3d q = face.d * face.n;
  int witnessFace = f;
  double lambda[3] = {1.0 / 3, 1.0 / 3, 1.0 / 3};
  double bestMin = -kInf;
  for (int g = 0; g < static_cast<int>(poly.faces.size()); ++g) {
    const Face& F = poly.faces[g];
    if (!F.alive || F.n.dot(face.n) < 0.5 || std::abs(F.n.dot(q) - F.d) > 64 * eps) continue;
    const Vector3d& w0 = poly.verts[F.v[0]].w;
    const Vector3d& w1 = poly.verts[F.v[1]].w;
    const Vector3d& w2 = poly.verts[F.v[2]].w;
    const double c[3] = {F.n.dot((w1 - q).cross(w2 - q)), F.n.dot((w2 - q).cross(w0 - q)),
                         F.n.dot((w0 - q).cross(w1 - q))};
    const double sum = c[0] + c[1] + c[2];
    if (!(sum > 0)) continue;
    const double m = std::min({c[0], c[1], c[2]}) / sum;
    if (m > bestMin) {
      bestMin = m;
      witnessFace = g;
      for (int k = 0; k < 3; ++k) lambda[k] = c[k] / sum;
    }
  }
  // Rounding can leave q a hair outside every face: clamp to the triangle and renormalise.
  double total = 0;
  for (double& l : lambda) total += (l = std::max(l, 0.0));
  r.pointA.setZero();
  r.pointB.setZero();
  const Face& W = poly.faces[witnessFace];
  for (int k = 0; k < 3; ++k) {
    r.pointA += (lambda[k] / total) * poly.verts[W.v[k]].a;
    r.pointB += (lambda[k] / total) * poly.verts[W.v[k]].b;
  }
  if (f == lastFace) r.witnessGap = lastGap;
  r.converged = r.originInside && !r.separated && r.depthUpper - r.depth <= tolerance && r.witnessGap <= tolerance;
  return r;
}

}  // namespace unidist::detail
