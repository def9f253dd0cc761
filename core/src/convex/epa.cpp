// Expanding polytope algorithm (van den Bergen, "Proximity Queries and Penetration Depth Computation on 3D
// Game Objects", GDC 2001) for the penetration depth of two overlapping convex sets.
//
// The polytope P is the convex hull of support points of D = A − B, so P ⊂ D. While P contains the origin,
// the origin's distance to P's closest face is a lower bound on the depth (dist(0, ∂D) >= dist(0, ∂P)), and
// h_D(n) for any unit n is an upper bound. Each step evaluates the support along the closest face's normal and
// adds it to P, replacing the faces it sees (a walk over face adjacency; the horizon is the boundary of the
// walked region). Convergence is linear on curved boundaries (~40 steps per factor 1000 on a sphere) and
// finite on polytopes.
//
// Robustness, each measure prompted by a failure seen in randomised stress runs:
//  * start polytope: the hull of the GJK simplex, the six axis supports and the supports along ± the normal of
//    the largest seed triangle: full-dimensional even when GJK stopped with a point, segment or triangle, and
//    it still contains the GJK simplex (hence the origin whenever GJK found it inside). Seeds that nearly
//    duplicate one already taken (a needle's supports) are skipped, except GJK's own points;
//  * an expansion is committed only if the horizon is one simple loop, every new face is non-degenerate, faces
//    away from a fixed interior point, leaves no neighbouring vertex clearly above it (no fold), and is not
//    closer to the origin than the current closest face (impossible in exact arithmetic: a sign of a normal
//    tilted by rounding). Otherwise it is retried with coarser visibility thresholds, then refused: EPA stops
//    with the bounds it has, never with a broken polytope;
//  * the origin just outside P (contact, or GJK stopping short of enclosing it) is handled: faces beyond which
//    it lies are expanded like any other, and P's nearest point to the origin (a real pair of points) gives an
//    upper bound, so contact comes out as ~0 with bounds straddling it;
//  * the answer: the closest face when converged or stalled by rounding; the best support direction when the
//    iteration cap stopped a still-progressing run (much better where the minimum translation direction is not
//    unique, e.g. concentric spheres, where the faces would have to tile the whole sphere).
#include "convex/gjk.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

namespace unidist::detail {
namespace {

using Eigen::Vector3d;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kFold = 4096;  // a vertex this many rounding levels above a new neighbouring face is a fold
                                // (nearly coplanar points on flat parts of D reach ~100; real folds ~1e13)

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
  // not give a valid closed polytope, or would bring a face closer to the origin than minDepth − slack (in exact
  // arithmetic a polytope that grows around the origin never does; if rounding says otherwise, a new face's
  // normal is untrustworthy, as happens for slivers when the new point is barely above the surface).
  bool insert(int vi, int f0, double minDepth = -kInf) {
    // A face whose visibility rounding decides (p nearly on its plane, or a sliver with a blurred normal) can
    // make the visible region non-convex; retry with coarser thresholds, which leave such faces in place.
    const double height = faces[f0].n.dot(verts[vi].w) - faces[f0].d;
    for (double threshold = eps_; threshold < height; threshold *= 1024)
      if (tryInsert(vi, f0, minDepth, threshold)) return true;
    return false;
  }

 private:
  bool tryInsert(int vi, int f0, double minDepth, double threshold) {
    const Vector3d p = verts[vi].w;
    ++pass_;
    removed_.clear();
    horizon_.clear();
    // Walk the faces p sees, from f0 across edges (an explicit stack: the region can be large). An edge whose
    // far face p does not see is on the horizon; each edge is crossed once, from its removed side.
    faces[f0].mark = pass_;
    removed_.push_back(f0);
    stack_.clear();
    for (int k = 0; k < 3; ++k) stack_.emplace_back(faces[f0].adj[k], faces[f0].adjEdge[k]);
    while (!stack_.empty()) {
      const auto [fi, e] = stack_.back();
      stack_.pop_back();
      Face& f = faces[fi];
      if (f.mark == pass_) continue;
      if (f.n.dot(p) - f.d <= threshold) {
        horizon_.emplace_back(fi, e);
        continue;
      }
      f.mark = pass_;
      removed_.push_back(fi);
      for (int k : {(e + 1) % 3, (e + 2) % 3}) stack_.emplace_back(f.adj[k], f.adjEdge[k]);
    }
    const int m = static_cast<int>(horizon_.size());
    if (m < 3) return false;
    std::vector<Face> fresh(m);
    for (int i = 0; i < m; ++i) {
      const Face& g = faces[horizon_[i].first];
      const int e = horizon_[i].second;
      if (!makeFace(g.v[(e + 1) % 3], g.v[e], vi, fresh[i])) return false;
      if (fresh[i].d < minDepth - 16 * eps_) return false;
      fresh[i].adj[0] = horizon_[i].first;
      fresh[i].adjEdge[0] = e;
    }
    // Link the fan around p: face i's edge v[1] → p meets face j's edge p → v[0] where fresh[j].v[0] == fresh[i].v[1].
    const int base = static_cast<int>(faces.size());
    std::vector<int> next(m, -1);
    for (int i = 0; i < m; ++i) {
      for (int j = 0; j < m; ++j) {
        if (fresh[j].v[0] != fresh[i].v[1]) continue;
        if (next[i] >= 0) return false;  // a vertex twice on the horizon: not a simple loop
        next[i] = j;
      }
      if (next[i] < 0) return false;
    }
    int steps = 0;
    for (int i = next[0]; i != 0 && steps <= m; i = next[i]) ++steps;
    if (steps != m - 1) return false;  // several loops: the visible region was not a disc
    // Local convexity, to precision: no neighbour's far vertex clearly above a new face (the kept face across
    // the horizon edge, and the next face of the fan). Rounding-decided visibility can otherwise fold the
    // surface, and a folded polytope misleads every later step.
    for (int i = 0; i < m; ++i) {
      const Face& g = faces[horizon_[i].first];
      const Face& F = fresh[i];
      if (F.n.dot(verts[g.v[(horizon_[i].second + 2) % 3]].w) - F.d > kFold * eps_) return false;
      if (F.n.dot(verts[fresh[next[i]].v[1]].w) - F.d > kFold * eps_) return false;
    }
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

  double eps_;
  Vector3d interior_ = Vector3d::Zero();
  int pass_ = 0;
  std::vector<int> removed_;
  std::vector<std::pair<int, int>> horizon_, stack_;  // (face, edge) pairs
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

EpaResult epa(const SupportFn& a, const SupportFn& b, const std::vector<SupportPoint>& seeds, int keep,
              double tolerance, int maxIterations, ConvexScale& scale) {
  EpaResult r;
  for (const SupportPoint& s : seeds) scale.coordMag = std::max(scale.coordMag, maxAbs(s));
  // Support along unit n, recording the bounds it proves (and the direction of the smallest h_D).
  double minH = kInf;
  SupportPoint bestSupport;
  Vector3d bestDir = Vector3d::UnitZ();
  auto support = [&](const Vector3d& n) {
    const SupportPoint s = minkowskiSupport(a, b, n);
    scale.coordMag = std::max(scale.coordMag, maxAbs(s));
    const double h = n.dot(s.w);
    r.signedLower = std::max(r.signedLower, -h);
    if (h < minH) {
      minH = h;
      bestSupport = s;
      bestDir = n;
    }
    return s;
  };

  // Seeds: the first `keep` (GJK's simplex, which may hold the origin) all, exact duplicates aside; the others
  // only if they are not within 1e-10 of the seeds' extent of one already taken. Near-duplicate points (a
  // needle's supports in neighbouring directions) would only make faces whose orientation is rounding.
  Eigen::AlignedBox3d box;
  for (const SupportPoint& s : seeds) box.extend(s.w);
  const double dupTol = 1e-10 * box.diagonal().norm();
  std::vector<SupportPoint> cand;
  for (int i = 0; i < static_cast<int>(seeds.size()); ++i) {
    bool dup = false;
    for (const SupportPoint& c : cand) dup = dup || (i < keep ? c.w == seeds[i].w : (c.w - seeds[i].w).norm() <= dupTol);
    if (!dup) cand.push_back(seeds[i]);
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

  // The closest point of a face's triangle to the origin, as barycentric coordinates.
  auto closestOnFace = [&poly](const Face& F) {
    const Vector3d pts[3] = {poly.verts[F.v[0]].w, poly.verts[F.v[1]].w, poly.verts[F.v[2]].w};
    return closestOnSimplex(pts, 3);
  };
  // The face whose triangle is nearest the origin, and the distance (used when the origin is outside: the face
  // with the smallest plane distance may then be far, e.g. with the origin beside one of its edges).
  auto nearestFace = [&poly, &closestOnFace](double& dist) {
    int best = -1;
    dist = kInf;
    for (int g = 0; g < static_cast<int>(poly.faces.size()); ++g) {
      if (!poly.faces[g].alive) continue;
      const double dg = closestOnFace(poly.faces[g]).v.norm();
      if (dg < dist) {
        dist = dg;
        best = g;
      }
    }
    return best;
  };
  // Upper bound on the signed distance proved by the polytope, given its closest face F by plane: −d when the
  // origin is inside, else the distance to the polytope (any of its points is a pair of points of A and B).
  auto upperFrom = [&](const Face& F) {
    if (F.d >= -eps) return -F.d;
    double dist = 0;
    nearestFace(dist);
    return dist;
  };

  double lastGap = kInf;
  int lastFace = -1;
  bool stalled = false;  // stopped by rounding (nothing to add, or an expansion refused), not by the cap
  for (int it = 0; it < maxIterations; ++it) {
    const int f = poly.closest();
    if (f < 0) break;
    const Vector3d n = poly.faces[f].n;
    const double d = poly.faces[f].d;
    const SupportPoint s = support(n);
    ++r.iterations;
    const double h = n.dot(s.w);
    // Stop on the interval this face proves (not on the best bounds so far), so that its witness points are
    // certified too: their depths in A and B sum to at most h + upper (= h − d when the origin is inside).
    lastGap = h + upperFrom(poly.faces[f]);
    lastFace = f;
    if (lastGap <= tolerance) break;
    if (h < -eps) break;  // D lies strictly below a plane through the origin: apart (GJK's case)
    // Stalled: the face is on D's boundary to working precision, or the expansion was refused.
    stalled = h - d <= eps;
    if (stalled) break;
    poly.verts.push_back(s);
    stalled = !poly.insert(static_cast<int>(poly.verts.size()) - 1, f, d >= -eps ? d : -kInf);
    if (stalled) break;
  }

  const int f = poly.closest();
  if (f < 0) {
    r.valid = false;
    return r;
  }
  const Face& face = poly.faces[f];
  r.originInside = face.d >= -eps;
  r.signedUpper = upperFrom(face);
  if (f == lastFace) r.witnessGap = lastGap;
  r.converged = r.signedUpper - r.signedLower <= tolerance && r.witnessGap <= tolerance;

  // Out of iterations while still progressing: the best support direction is the better estimate (it is exact
  // at once where the minimum translation direction is not unique, while the faces lag). Stalled by rounding:
  // the closest face is as good as the polytope gets, and it is the better one (exact in contact, for one).
  if (r.originInside && !r.converged && !stalled && minH < kInf) {
    r.distance = -minH;
    r.normal = bestDir;
    r.pointA = bestSupport.a;
    r.pointB = bestSupport.b;
    return r;
  }
  double lambda[3] = {0, 0, 0};
  int witnessFace = f;
  if (r.originInside) {
    // Barycentric coordinates of the origin's foot point q = d·n, carried to A's and B's support points. A
    // facet of a polytope D is triangulated into coplanar faces with equal d, and the heap may name any of
    // them: take, among the faces whose plane holds q, the one that contains q best (largest smallest
    // coordinate). Coordinates from a face not containing q would be clamped, moving the points off the sets.
    r.distance = -face.d;
    r.normal = face.n;
    const Vector3d q = face.d * face.n;
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
        for (int k = 0; k < 3; ++k) lambda[k] = std::max(c[k] / sum, 0.0);  // rounding can leave q a hair out
      }
    }
  } else {
    // The origin is just outside the polytope (contact, to the tolerance): the polytope's nearest point q gives
    // the distance and the points; the normal is the closest face's (by plane), along which the support was
    // evaluated, so it certifies the answer (q's own direction is only as good as the polytope there).
    double dist = 0;
    witnessFace = nearestFace(dist);
    const SubSimplex sub = closestOnFace(poly.faces[witnessFace]);
    for (int i = 0; i < sub.count; ++i) lambda[sub.index[i]] = sub.lambda[i];
    r.distance = sub.v.norm();
    r.normal = face.n;
  }
  const double total = lambda[0] + lambda[1] + lambda[2];
  if (!(total > 0)) lambda[0] = lambda[1] = lambda[2] = 1;
  const Face& W = poly.faces[witnessFace];
  r.pointA.setZero();
  r.pointB.setZero();
  for (int k = 0; k < 3; ++k) {
    const double l = lambda[k] / (total > 0 ? total : 3.0);
    r.pointA += l * poly.verts[W.v[k]].a;
    r.pointB += l * poly.verts[W.v[k]].b;
  }
  return r;
}

}  // namespace unidist::detail
