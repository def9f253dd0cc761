// NurbsModel: patches, closedness and orientation of solids, the global point query, support, surface cells.
#include "unidist/nurbs.h"

#include "lod/tessellate.h"
#include "nurbs/convex_support.h"
#include "nurbs/convexity_certificate.h"
#include "nurbs/objectives.h"
#include "nurbs/patch_search.h"
#include "nurbs/patch_tree.h"
#include "nurbs/point_cells.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory_resource>
#include <mutex>
#include <optional>

namespace unidist {
namespace {

/// The greatest n·S over the patch: its certified support value (support_bound.h), or where that is its control
/// points' (a wide arc is not concave as one piece), the greatest over its quarters, down to `depth` levels.
double supportUpper(const RationalBezierPatch& patch, const Eigen::Vector3d& n, int depth) {
  double net = -std::numeric_limits<double>::infinity();
  for (const Eigen::Vector4d& h : patch.net) net = std::max(net, n.dot(h.head<3>() / h[3]));
  const nurbs::SupportBound b = nurbs::certifySupport(patch, n);
  const double upper = b.proved ? std::min(b.upper, net) : net;
  if (depth == 0) return upper;
  double quarters = -std::numeric_limits<double>::infinity();
  for (int k = 0; k < 4; ++k) {
    const double s0 = 0.5 * (k % 2), t0 = 0.5 * (k / 2);
    quarters = std::max(quarters, supportUpper(nurbs::subpatch(patch, s0, s0 + 0.5, t0, t0 + 0.5), n, depth - 1));
  }
  return std::min(upper, quarters);
}

/// The model's box: per axis direction the greatest certified support value of the patches that can reach past
/// the others (their control points' box bounds the rest). The control points alone bound it too, but loosely
/// where arcs are wide: a torus written with 120° arcs (OpenCASCADE's) has control points at twice its radius.
Aabb certifiedBox(const std::vector<RationalBezierPatch>& patches) {
  constexpr int kDepth = 2;  // quarters of quarters: arcs of 30° of a 120° one
  Aabb box;
  for (int axis = 0; axis < 3; ++axis)
    for (double sign : {1.0, -1.0}) {
      const Eigen::Vector3d n = sign * Eigen::Vector3d::Unit(axis);
      double high = -std::numeric_limits<double>::infinity();
      for (const RationalBezierPatch& p : patches) {
        double net = -std::numeric_limits<double>::infinity();
        for (const Eigen::Vector4d& h : p.net) net = std::max(net, n.dot(h.head<3>() / h[3]));
        if (net > high) high = std::max(high, supportUpper(p, n, kDepth));
      }
      (sign > 0 ? box.max : box.min)[axis] = sign * high;
    }
  return box;
}

// Every distance is resolved to this fraction of the model size (the contract's default tolerance is 1e-9).
constexpr double kRelativeTolerance = 1e-13;
// A solid's surface must be closed to this fraction of the model size.
constexpr double kRelativeClosure = 1e-9;
// Unit normals of faces meeting at a point closer than this make no crease (a seam; a pole's nudged normals).
constexpr double kCreaseAngle = 1e-6;
// The point query's cells (point_cells.h): the grid reaches this fraction of the model size beyond its box, in
// cells this fraction of it across.
constexpr double kCellMargin = 0.5;
constexpr double kCellsAcross = 40;

std::string vec(const Eigen::Vector3d& v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.9g, %.9g, %.9g)", v.x(), v.y(), v.z());
  return buf;
}

// (s, t) moved onto the patch's edges where that moves its point x by no more than `snap` (a Newton run may stop
// a few ulps short of an edge).
void snapToEdges(const RationalBezierPatch& P, const Eigen::Vector3d& x, double snap, double& s, double& t) {
  const double s0 = s < 0.5 ? 0.0 : 1.0, t0 = t < 0.5 ? 0.0 : 1.0;
  if ((P.evaluate(s0, t) - x).norm() <= snap) s = s0;
  if ((P.evaluate(s, t0) - x).norm() <= snap) t = t0;
}

}  // namespace

NurbsModel::NurbsModel(std::vector<NurbsSurface> surfaces, bool solid) : surfaces_(std::move(surfaces)), solid_(solid) {
  if (surfaces_.empty()) throw InputError("a NURBS model needs at least one surface");
  for (std::size_t k = 0; k < surfaces_.size(); ++k)
    for (RationalBezierPatch& p : surfaces_[k].bezierPatches()) {
      patches_.push_back(std::move(p));
      patchSurface_.push_back(static_cast<int>(k));
    }
  forest_ = std::make_unique<nurbs::PatchForest>(patches_);
  standIns_ = std::make_unique<lod::StandInCache>();
  convexity_ = std::make_unique<Convexity>();
  bounds_ = certifiedBox(patches_);
  if (solid_) {
    checkClosed();
    if (enclosedVolume() < 0) orientation_ = -1;
    findIncidents();
  }
  for (const NurbsSurface& s : surfaces_) periodic_.push_back(findPeriodic(s));
  // Query cells (used once preparePointQueries() is called) over the model's box and half its size around it.
  const double size = bounds_.diagonal();
  const Eigen::Vector3d margin = Eigen::Vector3d::Constant(kCellMargin * size);
  cells_ = std::make_unique<nurbs::PointCells>(bounds_.min - margin, bounds_.max + margin, size / kCellsAcross);
}

struct NurbsModel::Convexity {
  std::once_flag once;
  nurbs::ConvexityVerdict verdict;
};

NurbsModel::~NurbsModel() = default;

bool NurbsModel::provedConvex(std::string* why) const {
  std::call_once(convexity_->once, [this] {
    convexity_->verdict = solid_ ? nurbs::certifyConvexSolid(patches_, orientation_, bounds_.diagonal())
                                 : nurbs::ConvexityVerdict{false, "an open surface set is not a solid"};
  });
  if (why) *why = convexity_->verdict.reason;
  return convexity_->verdict.proved;
}

std::array<bool, 2> NurbsModel::findPeriodic(const NurbsSurface& s) const {
  const double size = bounds_.diagonal();
  const Eigen::Vector2d lo(s.uMin(), s.vMin()), hi(s.uMax(), s.vMax());
  std::array<bool, 2> periodic{false, false};
  constexpr int kSamples = 9;
  for (int k = 0; k < 2; ++k) {
    bool same = true;
    for (int i = 0; i <= kSamples && same; ++i) {
      const double t = lo[1 - k] + (hi[1 - k] - lo[1 - k]) * i / kSamples;
      const Eigen::Vector3d a = k == 0 ? s.evaluate(lo[0], t) : s.evaluate(t, lo[1]);
      const Eigen::Vector3d b = k == 0 ? s.evaluate(hi[0], t) : s.evaluate(t, hi[1]);
      same = (a - b).norm() <= kRelativeClosure * size;
    }
    // An edge collapsed to a point (a pole) also "coincides": require the edge to have length.
    const Eigen::Vector3d e0 = s.evaluate(lo[0], lo[1]);
    const Eigen::Vector3d e1 = k == 0 ? s.evaluate(lo[0], 0.5 * (lo[1] + hi[1])) : s.evaluate(0.5 * (lo[0] + hi[0]), lo[1]);
    periodic[static_cast<std::size_t>(k)] = same && (e0 - e1).norm() > kRelativeClosure * size;
  }
  return periodic;
}

void NurbsModel::checkClosed() const {
  const double size = bounds_.diagonal(), tol = kRelativeClosure * size;
  for (std::size_t k = 0; k < patches_.size(); ++k) {
    const RationalBezierPatch& P = patches_[k];
    const int p = P.degreeU, q = P.degreeV;
    // Edge e: s = 0, s = 1, t = 0, t = 1. Sample its interior; a collapsed edge (a pole) needs no partner.
    for (int e = 0; e < 4; ++e) {
      const bool alongV = e < 2;  // s fixed, t varies
      const int fixed = (e % 2 == 0) ? 0 : (alongV ? p : q), count = alongV ? q : p;
      const Eigen::Vector3d first = alongV ? P.point(fixed, 0) : P.point(0, fixed);
      bool collapsed = true;
      for (int i = 1; i <= count; ++i)
        collapsed = collapsed && ((alongV ? P.point(fixed, i) : P.point(i, fixed)) - first).norm() <= tol;
      if (collapsed) continue;
      for (double a : {0.25, 0.5, 0.75}) {
        const double fs = (e % 2 == 0) ? 0.0 : 1.0;
        const Eigen::Vector3d x = alongV ? P.evaluate(fs, a) : P.evaluate(a, fs);
        const nurbs::SearchResult r = nurbs::minimise(*forest_, patches_, nurbs::PointObjective(x, size),
                                                      kRelativeTolerance * size, 0, static_cast<int>(k));
        if (!(r.best.value <= tol))
          throw InputError("\"solid\": true but the surfaces are not closed: the edge of patch " + std::to_string(k) +
                           " (surface " + std::to_string(patchSurface_[k]) + ") at " + vec(x) +
                           " has no neighbour (gap " + std::to_string(r.best.value) + ")");
      }
    }
  }
}

std::vector<NurbsModel::Incident> NurbsModel::incidentsAt(int k, const Eigen::Vector3d& x) const {
  const double size = bounds_.diagonal(), reach = kRelativeClosure * size;
  const double snap = 16 * std::numeric_limits<double>::epsilon() * size;
  std::vector<Incident> out;
  for (const auto& root : forest_->roots) {
    const int j = root->patch;
    if (j == k || (root->ball.center - x).norm() > root->ball.radius + reach || nurbs::boxDistance(*root, x) > reach)
      continue;
    const nurbs::SearchResult r = nurbs::minimise(*forest_, patches_, nurbs::PointObjective(x, size),
                                                  kRelativeTolerance * size, 0, -1, j);
    if (!(r.best.value <= reach)) continue;
    Incident in{j, r.best.s, r.best.t};
    snapToEdges(patches_[static_cast<std::size_t>(j)], r.best.point, snap, in.s, in.t);
    out.push_back(in);
  }
  return out;
}

void NurbsModel::findIncidents() {
  const double reach = kRelativeClosure * bounds_.diagonal();
  incidents_.resize(8 * patches_.size());
  for (std::size_t k = 0; k < patches_.size(); ++k) {
    const RationalBezierPatch& P = patches_[k];
    for (int c = 0; c < 4; ++c) incidents_[8 * k + c] = incidentsAt(static_cast<int>(k), P.evaluate(c & 1, c >> 1));
    for (int e = 0; e < 4; ++e) {
      // Edge e from (a0) to (a1) in (s, t); its neighbour must run along all of it, else the query searches.
      const Eigen::Vector2d a0 = e < 2 ? Eigen::Vector2d(e, 0) : Eigen::Vector2d(0, e - 2);
      const Eigen::Vector2d a1 = e < 2 ? Eigen::Vector2d(e, 1) : Eigen::Vector2d(1, e - 2);
      const Eigen::Vector2d mid = 0.5 * (a0 + a1);
      std::vector<Incident> along = incidentsAt(static_cast<int>(k), P.evaluate(mid[0], mid[1]));
      if (along.size() != 1) continue;
      const Incident& n = along.front();
      const RationalBezierPatch& Q = patches_[static_cast<std::size_t>(n.patch)];
      const bool onS = n.s == 0 || n.s == 1, onT = n.t == 0 || n.t == 1;
      if (onS == onT) continue;
      const Eigen::Vector3d b0 = onS ? Q.evaluate(n.s, 0) : Q.evaluate(0, n.t);
      const Eigen::Vector3d b1 = onS ? Q.evaluate(n.s, 1) : Q.evaluate(1, n.t);
      const Eigen::Vector3d e0 = P.evaluate(a0[0], a0[1]), e1 = P.evaluate(a1[0], a1[1]);
      const double forward = (b0 - e0).norm() + (b1 - e1).norm(), backward = (b0 - e1).norm() + (b1 - e0).norm();
      if (std::min(forward, backward) > 2 * reach) continue;
      // The neighbour's parameters at the edge's two ends (a query interpolates them for a first guess).
      Incident n0{n.patch, onS ? n.s : 0.0, onS ? 0.0 : n.t}, n1{n.patch, onS ? n.s : 1.0, onS ? 1.0 : n.t};
      if (backward < forward) std::swap(n0, n1);
      incidents_[8 * k + 4 + static_cast<std::size_t>(e)] = {n0, n1};
    }
  }
}

double NurbsModel::enclosedVolume() const {
  // Divergence theorem: V = 1/3 ∫∫ S·(Su x Sv) ds dt, midpoint rule (only the sign is used).
  constexpr int kSamples = 12;
  double volume = 0;
  for (const RationalBezierPatch& P : patches_)
    for (int i = 0; i < kSamples; ++i)
      for (int j = 0; j < kSamples; ++j) {
        const SurfaceDerivatives d = P.derivatives((i + 0.5) / kSamples, (j + 0.5) / kSamples);
        volume += d.point.dot(d.du.cross(d.dv));
      }
  return volume / (3.0 * kSamples * kSamples);
}

Eigen::Vector3d NurbsModel::patchNormal(int k, double s, double t) const {
  const RationalBezierPatch& P = patches_[static_cast<std::size_t>(k)];
  // At a collapsed edge (pole) Su x Sv vanishes: take the limit from just inside the patch.
  for (double nudge : {0.0, 1e-9, 1e-7, 1e-5, 1e-3}) {
    const double sn = s + nudge * (s < 0.5 ? 1 : -1), tn = t + nudge * (t < 0.5 ? 1 : -1);
    Eigen::Vector3d n;
    if (nurbs::unitNormal(P.derivatives(sn, tn), n)) return orientation_ * n;
  }
  return Eigen::Vector3d::UnitZ();  // a patch degenerate everywhere near (s, t): any unit vector
}

Eigen::Vector3d NurbsModel::normalAt(const nurbs::PatchHit& h) const {
  return h.normal.squaredNorm() > 0 ? Eigen::Vector3d(orientation_ * h.normal) : patchNormal(h.patch, h.s, h.t);
}

SurfacePoint NurbsModel::closestPoint(const Eigen::Vector3d& q_M) const {
  if (!q_M.allFinite()) throw InputError("NURBS point query: the query point is not finite");
  const double size = bounds_.diagonal();
  nurbs::SearchResult r;
  if (!prepared_ || !cells_->closest(*forest_, patches_, q_M, size, kRelativeTolerance * size, r))
    r = nurbs::minimise(*forest_, patches_, nurbs::PointObjective(q_M, size), kRelativeTolerance * size, 0);
  const nurbs::PatchHit& h = r.best;
  const RationalBezierPatch& P = patches_[static_cast<std::size_t>(h.patch)];
  SurfacePoint out;
  out.point = h.point;
  out.feature = patchSurface_[static_cast<std::size_t>(h.patch)];
  out.param = P.surfaceParam(h.s, h.t);
  out.error = std::max(0.0, h.value - r.lowerBound);
  const Eigen::Vector3d away = q_M - h.point;
  const double d = away.norm();
  // In a patch's interior the closest point is a critical point, q − p along the normal, whose sign is the side.
  // On a patch edge or corner every face meeting there decides (insideAtBoundary): the search is asked for no
  // ties (they held the faces at an edge only by chance).
  const bool boundary = solid_ && (h.s == 0 || h.s == 1 || h.t == 0 || h.t == 1);
  Eigen::Vector3d normal = normalAt(h);
  const bool inside = boundary ? insideAtBoundary(h, away, normal) : solid_ && away.dot(normal) < 0;
  if (d <= 4 * std::numeric_limits<double>::epsilon() * (q_M.norm() + size)) {  // on the surface
    out.signedDistance = d;
    out.normal = normal;
    return out;
  }
  out.signedDistance = inside ? -d : d;
  out.normal = inside ? Eigen::Vector3d(-away / d) : Eigen::Vector3d(away / d);
  return out;
}

namespace {

// One face of the solid's tangent cone at a point p of its surface: the tangent plane of a patch, or the part of
// it the patch covers at p: a half-plane (p on one patch edge: `edge` along it, `into` the patch) or a wedge
// (p a patch corner or on a collapsed edge: between the rays `edge` and `into`).
struct ConeFace {
  enum Kind { kPlane, kHalfPlane, kWedge } kind = kPlane;
  Eigen::Vector3d normal, edge, into;
  double distance = 0;  // from p + v (below)
  // The face's angle at p (the weight of its normal at the apex).
  double angle() const {
    return kind == kPlane ? 2 * M_PI : kind == kHalfPlane ? M_PI : std::acos(std::clamp(edge.dot(into), -1.0, 1.0));
  }
};

double rayDistance(const Eigen::Vector3d& v, const Eigen::Vector3d& ray) {
  const double along = v.dot(ray);
  return along > 0 ? (v - along * ray).norm() : v.norm();
}

// Distance from p + v to the face (within the linearised cone, whose apex is p).
double coneFaceDistance(const ConeFace& f, const Eigen::Vector3d& v) {
  const Eigen::Vector3d w = v - v.dot(f.normal) * f.normal;  // v in the face's plane
  switch (f.kind) {
    case ConeFace::kPlane:
      return std::abs(v.dot(f.normal));
    case ConeFace::kHalfPlane:
      return w.dot(f.into) >= 0 ? std::abs(v.dot(f.normal)) : (v - v.dot(f.edge) * f.edge).norm();
    case ConeFace::kWedge: {
      const Eigen::Vector3d axis = f.edge.cross(f.into);
      if (f.edge.cross(w).dot(axis) >= 0 && w.cross(f.into).dot(axis) >= 0) return std::abs(v.dot(f.normal));
      return std::min(rayDistance(v, f.edge), rayDistance(v, f.into));
    }
  }
  return v.norm();
}

}  // namespace

bool NurbsModel::insideAtBoundary(const nurbs::PatchHit& h, const Eigen::Vector3d& away,
                                  Eigen::Vector3d& normalSum) const {
  const double size = bounds_.diagonal(), reach = kRelativeClosure * size;
  const double snap = 16 * std::numeric_limits<double>::epsilon() * size;
  // The faces on the stack (a point is on a few patches).
  std::array<std::byte, 2048> stack;
  std::pmr::monotonic_buffer_resource memory(stack.data(), stack.size());
  std::pmr::vector<ConeFace> faces(&memory);
  faces.reserve(8);
  const auto addFaceAt = [&](int k, double s, double t, const SurfaceDerivatives& d) {
    const RationalBezierPatch& P = patches_[static_cast<std::size_t>(k)];
    ConeFace f;
    if (k == h.patch) f.normal = normalSum;
    else if (nurbs::unitNormal(d, f.normal)) f.normal *= orientation_;
    else f.normal = patchNormal(k, s, t);
    const bool onS = s == 0 || s == 1, onT = t == 0 || t == 1;
    const double scale = d.du.norm() + d.dv.norm();
    const bool flatS = d.du.norm() <= 1e-10 * scale, flatT = d.dv.norm() <= 1e-10 * scale;  // a collapsed edge
    // Unit directions into the patch along s (at t1) and along t (at s1).
    const double intoS = s < 0.5 ? 1 : -1, intoT = t < 0.5 ? 1 : -1;
    const auto inS = [&](double t1) { return Eigen::Vector3d(intoS * P.derivatives(s, t1).du.normalized()); };
    const auto inT = [&](double s1) { return Eigen::Vector3d(intoT * P.derivatives(s1, t).dv.normalized()); };
    if (onT && flatS) {  // a pole: the patch spans the wedge between its edges s = 0 and s = 1 leaving it
      f.kind = ConeFace::kWedge;
      f.edge = inT(0);
      f.into = inT(1);
    } else if (onS && flatT) {
      f.kind = ConeFace::kWedge;
      f.edge = inS(0);
      f.into = inS(1);
    } else if (onS && onT) {
      f.kind = ConeFace::kWedge;
      f.edge = intoS * d.du.normalized();
      f.into = intoT * d.dv.normalized();
    } else if (onS || onT) {
      f.kind = ConeFace::kHalfPlane;
      f.edge = (onS ? d.dv : d.du).normalized();
      const Eigen::Vector3d in = onS ? Eigen::Vector3d(intoS * d.du) : Eigen::Vector3d(intoT * d.dv);
      f.into = (in - in.dot(f.edge) * f.edge).normalized();
    }
    faces.push_back(f);
  };
  const auto addFace = [&](int k, double s, double t) {
    addFaceAt(k, s, t, patches_[static_cast<std::size_t>(k)].derivatives(s, t));
  };
  addFace(h.patch, h.s, h.t);
  // The other faces meeting at p: those through the same corner of the patch (or its collapsed edge: a pole), or
  // along the same edge, as found at construction (the search's own ties held them only by chance: it missed the
  // bottom face of a box under an edge). Where the edge has no known neighbour, or the neighbour's point at p is
  // not found, a search of each patch through p.
  const std::size_t base = 8 * static_cast<std::size_t>(h.patch);
  const bool onS = h.s == 0 || h.s == 1, onT = h.t == 0 || h.t == 1;
  const auto corner = [](double s, double t) { return static_cast<std::size_t>((s == 1 ? 1 : 0) + (t == 1 ? 2 : 0)); };
  bool known = true;
  if (onS && onT) {
    for (const Incident& in : incidents_[base + corner(h.s, h.t)]) addFace(in.patch, in.s, in.t);
  } else if (faces.front().kind == ConeFace::kWedge) {  // on a collapsed edge: any of its corners
    for (const Incident& in : incidents_[base + (onS ? corner(h.s, 0) : corner(0, h.t))]) addFace(in.patch, in.s, in.t);
  } else {
    // The neighbour's point at p: interpolated between the edge's ends (exact where the two share a
    // parametrisation, as a NURBS surface's patches and the box's faces do), else a Newton run from there.
    const std::vector<Incident>& ends = incidents_[base + 4 + (onS ? (h.s == 1 ? 1 : 0) : (h.t == 1 ? 3 : 2))];
    known = ends.size() == 2;
    if (known) {
      const int j = ends[0].patch;
      const RationalBezierPatch& Q = patches_[static_cast<std::size_t>(j)];
      const double a = onS ? h.t : h.s;
      const double s = ends[0].s + a * (ends[1].s - ends[0].s), t = ends[0].t + a * (ends[1].t - ends[0].t);
      const SurfaceDerivatives d = Q.derivatives(s, t);
      if ((d.point - h.point).norm() <= snap) {
        addFaceAt(j, s, t, d);
      } else {
        nurbs::PatchHit n = nurbs::polish(Q, j, nurbs::PointObjective(h.point, size), s, t);
        snapToEdges(Q, n.point, snap, n.s, n.t);
        known = n.value <= reach && (n.s == 0 || n.s == 1 || n.t == 0 || n.t == 1);
        if (known) addFace(j, n.s, n.t);
      }
    }
  }
  if (!known) {
    faces.resize(1);
    for (const Incident& in : incidentsAt(h.patch, h.point)) addFace(in.patch, in.s, in.t);
  }
  bool crease = false;
  for (const ConeFace& f : faces) crease = crease || (f.normal - faces.front().normal).norm() > kCreaseAngle;
  // A seam or a pole (every normal the same): q − p is along it.
  if (!crease) return away.dot(normalSum) < 0;
  // Near p the solid is its tangent cone (the faces above). Its nearest feature to q decides (the pseudonormal
  // rule of Bærentzen and Aanæs, exact for a polyhedral surface): a face by its normal, an edge the faces share
  // by the sum of their normals, the apex by the sum weighted by the faces' angles there.
  double nearest = std::numeric_limits<double>::infinity();
  for (ConeFace& f : faces) {
    f.distance = coneFaceDistance(f, away);
    nearest = std::min(nearest, f.distance);
  }
  const bool vertex =
      std::any_of(faces.begin(), faces.end(), [](const ConeFace& f) { return f.kind == ConeFace::kWedge; });
  const bool apex = vertex && nearest >= (1 - 1e-9) * away.norm();
  normalSum.setZero();
  Eigen::Vector3d pseudo = Eigen::Vector3d::Zero();
  for (const ConeFace& f : faces) {
    normalSum += f.normal;
    if (apex) pseudo += f.angle() * f.normal;
    else if (f.distance <= nearest + 1e-9 * away.norm()) pseudo += f.normal;
  }
  normalSum = normalSum.norm() > 1e-6 ? Eigen::Vector3d(normalSum.normalized()) : faces.front().normal;
  return away.dot(pseudo) < 0;
}

Eigen::Vector3d NurbsModel::support(const Eigen::Vector3d& dir_M) const {
  const double n = dir_M.norm();
  if (!(n > 0)) return forest_->roots.front()->corners[0];
  // The surface lies in its control points' hull: where the highest control point is a patch corner (a surface
  // point), it is the support point exactly — an axis direction on a revolved sphere, torus or box (a seam, a
  // pole or a vertex), where the search below must refine to 1e-13 about a point many patches share.
  if (const std::optional<Eigen::Vector3d> corner = nurbs::highestCornerIfTop(*forest_, dir_M)) return *corner;
  const double size = bounds_.diagonal();
  return nurbs::minimise(*forest_, patches_, nurbs::SupportObjective(dir_M / n, size), kRelativeTolerance * size, 0)
      .best.point;
}

std::vector<SurfaceCell> NurbsModel::surfaceCells() const {
  std::vector<SurfaceCell> cells;
  for (const auto& root : forest_->roots) {
    SurfaceCell c;
    c.center = root->ball.center;
    c.radius = root->ball.radius;
    c.sample = root->net.evaluate(0.5, 0.5);
    c.face = root->patch;
    c.u0 = 0;
    c.u1 = 1;
    c.v0 = 0;
    c.v1 = 1;
    cells.push_back(c);
  }
  return cells;
}

void NurbsModel::splitCell(const SurfaceCell& cell, std::vector<SurfaceCell>& out) const {
  const RationalBezierPatch& P = patches_[static_cast<std::size_t>(cell.face)];
  const double um = 0.5 * (cell.u0 + cell.u1), vm = 0.5 * (cell.v0 + cell.v1);
  for (int k = 0; k < 4; ++k) {
    SurfaceCell c = cell;
    c.u0 = k & 1 ? um : cell.u0;
    c.u1 = k & 1 ? cell.u1 : um;
    c.v0 = k & 2 ? vm : cell.v0;
    c.v1 = k & 2 ? cell.v1 : vm;
    const RationalBezierPatch piece = nurbs::subpatch(P, c.u0, c.u1, c.v0, c.v1);
    const BoundingSphere ball = nurbs::ballOfNet(piece.net);
    c.center = ball.center;
    c.radius = ball.radius;
    c.sample = P.evaluate(0.5 * (c.u0 + c.u1), 0.5 * (c.v0 + c.v1));
    out.push_back(c);
  }
}

std::string NurbsModel::describe() const {
  int maxU = 0, maxV = 0;
  for (const NurbsSurface& s : surfaces_) {
    maxU = std::max(maxU, s.degreeU());
    maxV = std::max(maxV, s.degreeV());
  }
  const Eigen::Vector3d e = bounds_.max - bounds_.min;
  char buf[256];
  std::snprintf(buf, sizeof buf, "nurbs: %zu surface%s, %zu rational Bezier patches, degree up to %dx%d, %s, extent %.6g x %.6g x %.6g",
                surfaces_.size(), surfaces_.size() == 1 ? "" : "s", patches_.size(), maxU, maxV,
                solid_ ? "solid" : "open surface", e.x(), e.y(), e.z());
  return buf;
}

std::size_t NurbsModel::patchTreeBytes() const {
  std::size_t roots = 0;  // the roots' nets are the patches' (counted with them); their points are the tree's
  for (const auto& root : forest_->roots) roots += sizeof(nurbs::PatchNode) + root->points.capacity() * sizeof(Eigen::Vector3d);
  // The per-patch tables made with the roots: poles, distinct corners.
  std::size_t tables = forest_->poleOfEdge.capacity() * sizeof(std::array<int, 4>) +
                       forest_->distinctCorners.capacity() * sizeof(nurbs::PatchForest::Corner);
  for (const nurbs::PatchForest::Pole& p : forest_->poles) tables += sizeof(p) + p.edges.capacity() * sizeof(p.edges[0]);
  return forest_->bytes.load() + roots + tables;
}

std::vector<StructureReport> NurbsModel::structures() const {
  return {{"patch-tree", true, patchTreeBytes()}, standIns_->report(), {"point-cells", cells_->built(), cells_->bytes()}};
}

StandIn NurbsModel::atDetail(double maxDeviation) const {
  lod::checkLevel(maxDeviation);
  if (maxDeviation == 0) return StandIn{this, 0.0};
  return standIns_->get(*this, maxDeviation, [this](double level) { return lod::tessellate(*this, level); });
}

std::size_t NurbsModel::memoryBytes() const {
  std::size_t bytes = sizeof(*this) + patchTreeBytes() + cells_->bytes() + standIns_->report().bytes;
  for (const NurbsSurface& s : surfaces_)
    bytes += sizeof(s) + (s.knotsU().size() + s.knotsV().size()) * sizeof(double) +
             static_cast<std::size_t>(s.countU() * s.countV()) * sizeof(Eigen::Vector4d);
  for (const RationalBezierPatch& p : patches_) bytes += sizeof(p) + 2 * p.net.size() * sizeof(Eigen::Vector4d);
  for (const std::vector<Incident>& v : incidents_) bytes += sizeof(v) + v.capacity() * sizeof(Incident);
  return bytes;
}

}  // namespace unidist
