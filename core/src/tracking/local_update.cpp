// Local update of one tracked minimum (tracking/local_update.h).
#include "tracking/local_update.h"

#include "mesh/triangle_triangle.h"
#include "unidist/mesh.h"
#include "unidist/nurbs.h"

#include <Eigen/LU>
#include <Eigen/QR>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace unidist::tracking {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The contract normal in A's frame of a reading anchored on A (pA, B's answer sB in B's frame): B's outward
/// normal at its point faces A's point, the contact normal is its opposite.
Eigen::Vector3d normalFromB(const SurfacePoint& sB, const Eigen::Isometry3d& X_AB) {
  return -(X_AB.linear() * sB.normal);
}

}  // namespace

LocalUpdater::LocalUpdater(const Model& a, const Model& b, double tol, int maxIterations)
    : a_(a), b_(b), la_(LocalSurface::make(a)), lb_(LocalSurface::make(b)), tol_(tol), maxIterations_(maxIterations) {
  const auto* na = dynamic_cast<const NurbsModel*>(&a);
  const auto* nb = dynamic_cast<const NurbsModel*>(&b);
  if (na && nb) {
    nurbsA_ = std::make_unique<ModelParams>(*na);
    nurbsB_ = std::make_unique<ModelParams>(*nb);
  }
  reachA_ = a.localBoundingSphere().radius;
  reachB_ = b.localBoundingSphere().radius;
  const double da = a.localBounds().diagonal(), db = b.localBounds().diagonal();
  size_ = std::isfinite(da) && std::isfinite(db) ? std::min(da, db) : (std::isfinite(da) ? da : db);
}

LocalUpdater::~LocalUpdater() = default;

LocalMinimum LocalUpdater::fromWorld(const Eigen::Vector3d& pA_W, const Eigen::Vector3d& pB_W, double distance,
                                     const Eigen::Vector3d& normal_W, const Eigen::Isometry3d& X_WA,
                                     const Eigen::Isometry3d& X_WB) const {
  LocalMinimum m;
  m.pA_A = X_WA.inverse() * pA_W;
  m.pB_B = X_WB.inverse() * pB_W;
  m.hintA = la_->hintOf(a_.closestPoint(m.pA_A));
  m.hintB = lb_->hintOf(b_.closestPoint(m.pB_B));
  m.distance = distance;
  m.normal_A = X_WA.linear().transpose() * normal_W;
  return m;
}

bool LocalUpdater::update(LocalMinimum& m, const Eigen::Isometry3d& X_AB, Work& work) const {
  if (nurbsA_) {
    LocalMinimum trial = m;
    if (nurbsPair(trial, X_AB, work)) {
      m = trial;
      return true;
    }
    ++work.fallbacks;  // a pole, a boundary, or the branch ended: the generic routine takes over
  }
  if (m.distance < 0 && (a_.isSolid() || b_.isSolid())) overlap(m, X_AB, work);
  if (!(m.distance < 0) && !apart(m, X_AB, work)) overlap(m, X_AB, work);
  if (!std::isfinite(m.distance)) return false;
  // The contract exactly (pointB − pointA = distance · normal) where the points are apart: an overlap reading
  // that stopped short of its extremum has points not quite along its normal.
  const Eigen::Vector3d r = X_AB * m.pB_B - m.pA_A;
  const double length = r.norm();
  if (length > 1e-12 * (1 + m.pA_A.cwiseAbs().maxCoeff())) {
    const double sign = r.dot(m.normal_A) < 0 ? -1.0 : 1.0;
    m.distance = sign * length;
    m.normal_A = r / m.distance;
  }
  return true;
}

// Unknowns x = (u, v) on A's surface, (s, t) on B's. Equations, in A's frame with r = P_B − P_A and n A's unit
// normal: r·A_u = r·A_v = 0 (B's point on A's normal line) and n·B_s = n·B_t = 0 (the normals parallel). Unlike
// the symmetric form r·B_s = r·B_t = 0 these stay regular when r → 0, so a minimum is followed through touching
// into overlap. A root whose outward normals point the same way is another kind of extremum (a far side): lost.
bool LocalUpdater::nurbsPair(LocalMinimum& m, const Eigen::Isometry3d& X_AB, Work& work) const {
  const auto& A = static_cast<const NurbsModel&>(a_);
  const auto& B = static_cast<const NurbsModel&>(b_);
  const int na = static_cast<int>(A.surfaces().size()), nb = static_cast<int>(B.surfaces().size());
  if (m.hintA.feature < 0 || m.hintA.feature >= na || m.hintB.feature < 0 || m.hintB.feature >= nb) return false;
  const NurbsSurface& sa = A.surfaces()[static_cast<std::size_t>(m.hintA.feature)];
  const NurbsSurface& sb = B.surfaces()[static_cast<std::size_t>(m.hintB.feature)];
  const SurfaceParams& pa = nurbsA_->of(m.hintA.feature);
  const SurfaceParams& pb = nurbsB_->of(m.hintB.feature);
  const Eigen::Matrix3d R = X_AB.linear();
  const double size = std::max(A.localBounds().diagonal(), B.localBounds().diagonal());

  struct State {
    Eigen::Vector4d x;
    SurfaceDerivatives a, b;  // b in A's frame
    Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
    double cross = 0;         // |A_u × A_v|
    Eigen::Vector4d E = Eigen::Vector4d::Zero();
    double merit = kInf;
  };
  auto evaluate = [&](const Eigen::Vector4d& x, State& s) {
    s.x = x;
    s.a = sa.derivatives(x[0], x[1]);
    const SurfaceDerivatives bl = sb.derivatives(x[2], x[3]);
    s.b.point = X_AB * bl.point;
    s.b.du = R * bl.du, s.b.dv = R * bl.dv, s.b.duu = R * bl.duu, s.b.duv = R * bl.duv, s.b.dvv = R * bl.dvv;
    const Eigen::Vector3d N = s.a.du.cross(s.a.dv);
    s.cross = N.norm();
    if (!(s.cross > 1e-10 * (s.a.du.squaredNorm() + s.a.dv.squaredNorm()))) return false;  // a pole
    s.n = N / s.cross;
    const Eigen::Vector3d r = s.b.point - s.a.point;
    s.E << r.dot(s.a.du), r.dot(s.a.dv), s.n.dot(s.b.du), s.n.dot(s.b.dv);
    // Merit in lengths: the tangential offset of B's point and the normals' misalignment times the model size.
    const double lu = s.a.du.norm(), lv = s.a.dv.norm(), ls = s.b.du.norm(), lt = s.b.dv.norm();
    if (!(lu > 0 && lv > 0 && ls > 0 && lt > 0)) return false;
    s.merit = std::pow(s.E[0] / lu, 2) + std::pow(s.E[1] / lv, 2) + std::pow(size * s.E[2] / ls, 2) +
              std::pow(size * s.E[3] / lt, 2);
    return true;
  };
  auto wrapped = [&](const Eigen::Vector4d& x, Eigen::Vector4d& y) {
    const Eigen::Vector2d xa = x.head<2>(), xb = x.tail<2>();
    if (!pa.inside(xa) || !pb.inside(xb)) return false;  // leaving an open domain: the boundary is not ours
    y << pa.wrap(xa), pb.wrap(xb);
    return true;
  };

  State s;
  Eigen::Vector4d x0;
  if (!wrapped((Eigen::Vector4d() << m.hintA.param, m.hintB.param).finished(), x0) || !evaluate(x0, s)) return false;
  bool converged = false;
  for (int it = 0; it < maxIterations_ && !converged; ++it) {
    ++work.newton;
    const Eigen::Vector3d r = s.b.point - s.a.point;
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - s.n * s.n.transpose();
    const Eigen::Vector3d nu = P * (s.a.duu.cross(s.a.dv) + s.a.du.cross(s.a.duv)) / s.cross;
    const Eigen::Vector3d nv = P * (s.a.duv.cross(s.a.dv) + s.a.du.cross(s.a.dvv)) / s.cross;
    const SurfaceDerivatives &a = s.a, &b = s.b;
    Eigen::Matrix4d J;  // rows: the four equations; columns: u, v, s, t
    J << -a.du.dot(a.du) + r.dot(a.duu), -a.dv.dot(a.du) + r.dot(a.duv), b.du.dot(a.du), b.dv.dot(a.du),
        -a.du.dot(a.dv) + r.dot(a.duv), -a.dv.dot(a.dv) + r.dot(a.dvv), b.du.dot(a.dv), b.dv.dot(a.dv),
        nu.dot(b.du), nv.dot(b.du), s.n.dot(b.duu), s.n.dot(b.duv),
        nu.dot(b.dv), nv.dot(b.dv), s.n.dot(b.duv), s.n.dot(b.dvv);
    const Eigen::FullPivLU<Eigen::Matrix4d> lu(J);
    if (!lu.isInvertible()) return false;
    const Eigen::Vector4d step = -lu.solve(s.E);
    if (!step.allFinite()) return false;
    double scale = 1;
    bool accepted = false;
    for (int half = 0; half < 8; ++half, scale *= 0.5) {  // Newton with backtracking on the merit
      Eigen::Vector4d y;
      State t;
      if (!wrapped(s.x + scale * step, y) || !evaluate(y, t)) continue;
      if (t.merit < s.merit || t.merit <= tol_ * tol_) {
        const double moved = (t.a.point - s.a.point).norm() + (t.b.point - s.b.point).norm();
        s = t;
        accepted = true;
        converged = moved <= 0.01 * tol_ || s.merit <= 1e-4 * tol_ * tol_;
        break;
      }
    }
    if (!accepted) converged = s.merit <= tol_ * tol_;  // at the root to rounding, or stuck
    if (!accepted && !converged) return false;
  }
  if (!converged || !(s.merit <= tol_ * tol_)) return false;
  const double orientA = A.orientation(), orientB = B.orientation();
  const Eigen::Vector3d outA = orientA * s.n;
  const Eigen::Vector3d nB = s.b.du.cross(s.b.dv);
  if (A.isSolid() && B.isSolid() && orientB * nB.dot(outA) > 0) return false;  // both normals one way: not a contact
  const Eigen::Vector3d r = s.b.point - s.a.point;
  const double d = r.dot(outA);
  m.hintA = {m.hintA.feature, s.x.head<2>()};
  m.hintB = {m.hintB.feature, s.x.tail<2>()};
  m.pA_A = s.a.point;
  m.pB_B = X_AB.inverse() * s.b.point;
  m.distance = (A.isSolid() && B.isSolid()) ? d : std::abs(d);
  const double len = r.norm();
  m.normal_A = len > 1e-12 * (1 + s.a.point.cwiseAbs().maxCoeff()) ? Eigen::Vector3d(r / (m.distance < 0 ? -len : len))
                                                                     : outA;
  return true;
}

// Johnson & Cohen's alternation with local projections: each half-step can only shorten the segment (the
// previous pair is a witness), so the distance decreases to a local minimum. Plain alternation converges
// linearly with the rate r_A·r_B / ((r_A + d)(r_B + d)) per principal direction (radii of curvature r, gap d):
// close to 1 for nearly touching curved surfaces (measured: 0.75 per step for a ball 0.08 from a torus), so
// the fixed-point map x → B(A(x)) is accelerated (Anderson mixing over the last three steps, exact for a map
// that is linear on a plane), and an accelerated step is kept only when it shortens the segment. Stops when the
// point of B stops moving (not the distance: it is flat at a minimum, second order in the points' error), after
// maxIterations, or when either point is inside the other solid (the overlap routine takes over).
bool LocalUpdater::alternateApart(LocalMinimum& m, const Eigen::Isometry3d& X_AB, Work& work) const {
  const Eigen::Isometry3d X_BA = X_AB.inverse();
  struct Step {
    Eigen::Vector3d x, y;  // from x (B's frame, anywhere) to y, B's point closest to A's point closest to x
    SurfacePoint sA, sB;
    Hint hA, hB;
  };
  auto step = [&](const Eigen::Vector3d& x, Hint hA, Hint hB) {
    Step s;
    s.x = x;
    s.sA = la_->project(X_AB * x, hA, work);
    s.sB = lb_->project(X_BA * s.sA.point, hB, work);
    s.y = s.sB.point;
    s.hA = hA, s.hB = hB;
    return s;
  };
  auto overlapping = [](const Step& s) { return s.sA.signedDistance < 0 || s.sB.signedDistance < 0; };
  Step cur = step(m.pB_B, m.hintA, m.hintB);
  std::array<Step, 3> history;  // the last plain or mixed steps, oldest first (no allocation at servo rate)
  std::size_t kept = 0;
  for (int it = 1;; ++it) {
    m.pA_A = cur.sA.point, m.pB_B = cur.sB.point, m.hintA = cur.hA, m.hintB = cur.hB;
    m.distance = cur.sB.signedDistance;
    m.normal_A = normalFromB(cur.sB, X_AB);
    if (overlapping(cur)) {
      m.distance = std::min(cur.sA.signedDistance, cur.sB.signedDistance);
      return false;
    }
    if ((cur.y - cur.x).norm() <= tol_ || it >= maxIterations_) return true;
    if (kept == history.size()) std::rotate(history.begin(), history.begin() + 1, history.end()), --kept;
    history[kept++] = cur;
    Eigen::Vector3d next = cur.y;
    if (kept >= 2) {
      const int k = static_cast<int>(kept) - 1;
      Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 2> dF(3, k), dY(3, k);  // on the stack
      for (int j = 0; j < k; ++j) {
        const Step& p = history[static_cast<std::size_t>(j)];
        const Step& q = history[static_cast<std::size_t>(j + 1)];
        dF.col(j) = (q.y - q.x) - (p.y - p.x);
        dY.col(j) = q.y - p.y;
      }
      const Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 2, 1> gamma = dF.colPivHouseholderQr().solve(cur.y - cur.x);
      const Eigen::Vector3d accelerated = cur.y - dY * gamma;
      if (accelerated.allFinite()) next = accelerated;
    }
    Step trial = step(next, cur.hA, cur.hB);
    if (!overlapping(trial) && trial.sB.signedDistance > cur.sB.signedDistance && next != cur.y) {
      kept = 0;  // the mixing overshot: a plain step, which cannot lengthen the segment
      trial = step(cur.y, cur.hA, cur.hB);
    }
    cur = trial;
  }
}

bool LocalUpdater::apart(LocalMinimum& m, const Eigen::Isometry3d& X_AB, Work& work) const {
  if (la_->mesh() && lb_->mesh() && !meshPairDescent(m, X_AB, work)) return false;
  return alternateApart(m, X_AB, work);
}

// Overlap. Two meshes: the locally deepest vertex of each inside the other (what contacts() reports for them).
// Two other solids: the local penetration extremum (below). A model without an inside (a cloud, an open
// surface): its locally deepest point inside the solid (contract: min over its points of the solid's signed
// distance).
void LocalUpdater::overlap(LocalMinimum& m, const Eigen::Isometry3d& X_AB, Work& work) const {
  if (a_.isSolid() && b_.isSolid() && !(la_->hasVertexGraph() && lb_->hasVertexGraph())) {
    liftedOverlap(m, X_AB, work);
    return;
  }
  LocalMinimum best = m;
  best.distance = kInf;
  if (b_.isSolid()) {
    const LocalMinimum r = deepestOf(true, m, X_AB, work);
    if (r.distance < best.distance) best = r;
  }
  if (a_.isSolid()) {
    const LocalMinimum r = deepestOf(false, m, X_AB, work);
    if (r.distance < best.distance) best = r;
  }
  if (std::isfinite(best.distance)) m = best;
  // Two meshes crossing with no vertex inside the other (an edge through an edge): the local penetration
  // extremum, as contacts() answers with the global one there.
  if (!(m.distance < 0) && a_.isSolid() && b_.isSolid()) liftedOverlap(m, X_AB, work);
}

// The penetration extremum of two solids (outward normals opposite, the segment along them) is the closest pair
// of the same solids once B is lifted out along the contact normal n by more than the depth (the skin of
// contact_manifold.h): exact for a translation, so each material point keeps its place on its model. The lifted
// pair is apart and converges under the accelerated alternation; its normal n' becomes the next lift direction.
// n' differs from n by the factor s / (s + |c|) on spheres (s the lift, c the centres' distance), small for the
// shallow overlaps of contact, so a few rounds settle n.
void LocalUpdater::liftedOverlap(LocalMinimum& m, const Eigen::Isometry3d& X_AB, Work& work) const {
  Eigen::Vector3d n = m.normal_A;
  double lift = 2 * std::max(-m.distance, 0.0) + 1e-3 * size_;
  for (int round = 0; round < 8; ++round) {
    Eigen::Isometry3d X_lifted = X_AB;
    X_lifted.pretranslate(lift * n);
    LocalMinimum t = m;
    if (!apart(t, X_lifted, work)) {
      lift *= 2;  // still overlapping: the overlap is deeper than the reading it started from
      continue;
    }
    const Eigen::Vector3d next = t.normal_A;
    m.pA_A = t.pA_A, m.pB_B = t.pB_B, m.hintA = t.hintA, m.hintB = t.hintB;
    m.normal_A = next;
    m.distance = (X_AB * t.pB_B - t.pA_A).dot(next);
    const bool settled = (next - n).norm() <= 1e-12 + tol_ / size_;
    n = next;
    if (settled) return;
    lift = 2 * std::max(-m.distance, 0.0) + 1e-3 * size_;
  }
}

// Two meshes apart: Johnson's local descent over triangle pairs — from the cached pair, move to the triangle of
// either ring (the triangles sharing a vertex with the current one) whose exact triangle–triangle distance to the
// other's current triangle is smaller, until neither improves. Exact on facets, where alternating projections
// between two nearly parallel faces crawl (rate cos² of their angle). False when it met crossing triangles.
bool LocalUpdater::meshPairDescent(LocalMinimum& m, const Eigen::Isometry3d& X_AB, Work& work) const {
  const TriangleMesh& A = *la_->mesh();
  const TriangleMesh& B = *lb_->mesh();
  const int countA = static_cast<int>(A.triangles().size()), countB = static_cast<int>(B.triangles().size());
  int ta = m.hintA.feature, tb = m.hintB.feature;
  if (ta < 0 || ta >= countA || tb < 0 || tb >= countB) return true;
  auto corners = [](const TriangleMesh& mesh, int t, const Eigen::Isometry3d& X, Eigen::Vector3d* out) {
    const auto& tri = mesh.triangles()[static_cast<std::size_t>(t)];
    for (int k = 0; k < 3; ++k) out[k] = X * mesh.vertices()[tri[static_cast<std::size_t>(k)]];
  };
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  Eigen::Vector3d va[3], vb[3];
  corners(A, ta, I, va);
  corners(B, tb, X_AB, vb);
  const Eigen::Matrix3d& R = X_AB.linear();
  mesh::TriangleTriangleClosest best = mesh::closestTriangleTriangle(va, A.faceNormal(ta), vb, R * B.faceNormal(tb));
  std::vector<int> ring;
  for (int it = 0; it < maxIterations_ && !best.intersecting && best.distance > 0; ++it) {
    ++work.steps;
    bool moved = false;
    la_->triangleRing(ta, ring);
    corners(B, tb, X_AB, vb);
    const Eigen::Vector3d nb = R * B.faceNormal(tb);
    for (int u : ring) {
      if (u == ta) continue;
      corners(A, u, I, va);
      const auto c = mesh::closestTriangleTriangle(va, A.faceNormal(u), vb, nb, best.distance);
      if (c.distance < best.distance) best = c, ta = u, moved = true;
    }
    lb_->triangleRing(tb, ring);
    corners(A, ta, I, va);
    for (int w : ring) {
      if (w == tb) continue;
      corners(B, w, X_AB, vb);
      const auto c = mesh::closestTriangleTriangle(va, A.faceNormal(ta), vb, R * B.faceNormal(w), best.distance);
      if (c.distance < best.distance) best = c, tb = w, moved = true;
    }
    if (!moved) break;
  }
  // The alternation that follows starts from these points: it fixes the signs, normal and parameters, and
  // detects an overlap (the descent itself is unsigned).
  m.hintA.feature = ta, m.hintB.feature = tb;
  m.pA_A = best.pointA;
  m.pB_B = X_AB.inverse() * best.pointB;
  return !best.intersecting;
}

// Minimises the other model's signed distance over the anchor's surface near the anchor point: over a mesh's
// vertex graph (what contacts() reports for overlapping meshes), else by support probes: the anchor's point
// locally closest to a probe pushed out along the contact normal is the locally extreme point in that direction.
LocalMinimum LocalUpdater::deepestOf(bool anchorA, const LocalMinimum& start, const Eigen::Isometry3d& X_AB,
                                               Work& work) const {
  const LocalSurface& anchor = anchorA ? *la_ : *lb_;
  const LocalSurface& other = anchorA ? *lb_ : *la_;
  const Eigen::Isometry3d X_OA = anchorA ? X_AB.inverse() : X_AB;  // anchor's frame → other's
  const double reach = anchorA ? reachA_ : reachB_;
  Hint anchorHint = anchorA ? start.hintA : start.hintB;
  Hint otherHint = anchorA ? start.hintB : start.hintA;
  // Reading at an anchor point p (anchor frame): the other's signed distance there, the contact normal in the
  // anchor's frame pointing the way the other must move (into the other's inside, for an overlap).
  struct Reading {
    Eigen::Vector3d p, q;  // anchor's point (anchor frame), other's point (other frame)
    Hint hp, hq;
    double d = kInf;
    Eigen::Vector3d inward = Eigen::Vector3d::UnitZ();  // anchor frame: minus the other's outward normal
  };
  auto read = [&](const Eigen::Vector3d& p, const Hint& hp, Hint hq) {
    const SurfacePoint s = other.project(X_OA * p, hq, work);
    Reading r{p, s.point, hp, hq, s.signedDistance, X_OA.linear().transpose() * -s.normal};
    return r;
  };
  Reading cur = read(anchorA ? start.pA_A : start.pB_B, anchorHint, otherHint);
  if (anchor.hasVertexGraph()) {
    int v = anchor.nearestVertex(cur.hp, cur.p);
    cur = read(anchor.vertex(v), anchor.vertexHint(v), cur.hq);
    std::vector<int> around;
    for (int it = 0; it < maxIterations_; ++it) {
      ++work.steps;
      anchor.vertexNeighbours(v, around);
      int next = v;
      Reading best = cur;
      for (int w : around) {
        const Reading r = read(anchor.vertex(w), anchor.vertexHint(w), cur.hq);
        if (r.d < best.d) best = r, next = w;
      }
      if (next == v) break;
      v = next, cur = best;
    }
  } else {
    for (int it = 0; it < maxIterations_; ++it) {
      Hint h = cur.hp;
      const SurfacePoint s = anchor.project(cur.p + reach * cur.inward, h, work);
      const Reading r = read(s.point, h, cur.hq);
      if (!(r.d < cur.d)) break;
      const bool small = cur.d - r.d <= 0.1 * tol_;
      cur = r;
      if (small) break;
    }
  }
  LocalMinimum m = start;
  m.distance = cur.d;
  if (anchorA) {
    m.pA_A = cur.p, m.pB_B = cur.q, m.hintA = cur.hp, m.hintB = cur.hq;
    m.normal_A = cur.inward;  // minus B's outward normal: from A toward B, or the way B moves out of A
  } else {
    m.pB_B = cur.p, m.pA_A = cur.q, m.hintB = cur.hp, m.hintA = cur.hq;
    m.normal_A = -(X_AB.linear() * cur.inward);  // A's outward normal
  }
  return m;
}

}  // namespace unidist::tracking
