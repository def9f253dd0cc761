// NurbsModel: patches, closedness and orientation of solids, the global point query, support, surface cells.
#include "unidist/nurbs.h"

#include "lod/tessellate.h"
#include "nurbs/objectives.h"
#include "nurbs/patch_search.h"
#include "nurbs/patch_tree.h"

#include <cmath>
#include <cstdio>
#include <limits>

namespace unidist {
namespace {

// Every distance is resolved to this fraction of the model size (the contract's default tolerance is 1e-9).
constexpr double kRelativeTolerance = 1e-13;
// Candidates within this fraction of the model size of the best distance are ties (their normals decide the side).
constexpr double kRelativeTie = 1e-9;
// A solid's surface must be closed to this fraction of the model size.
constexpr double kRelativeClosure = 1e-9;

std::string vec(const Eigen::Vector3d& v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.9g, %.9g, %.9g)", v.x(), v.y(), v.z());
  return buf;
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
  // Bounds: the box of the Euclidean control points (convex hull property). Exact for the conic models whose
  // extreme control points lie on the surface (sphere, torus, cylinder); conservative otherwise. (The support
  // searches that would make it tight are slow at poles, where the cells along a collapsed edge all reach the
  // extreme point.)
  for (const RationalBezierPatch& p : patches_)
    for (const Eigen::Vector4d& h : p.net) bounds_.extend(h.head<3>() / h[3]);
  if (solid_) {
    checkClosed();
    if (enclosedVolume() < 0) orientation_ = -1;
  }
  for (const NurbsSurface& s : surfaces_) periodic_.push_back(findPeriodic(s));
}

NurbsModel::~NurbsModel() = default;

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
  const nurbs::SearchResult r =
      nurbs::minimise(*forest_, patches_, nurbs::PointObjective(q_M, size), kRelativeTolerance * size, kRelativeTie * size);
  const nurbs::PatchHit& h = r.best;
  const RationalBezierPatch& P = patches_[static_cast<std::size_t>(h.patch)];
  SurfacePoint out;
  out.point = h.point;
  out.feature = patchSurface_[static_cast<std::size_t>(h.patch)];
  out.param = P.surfaceParam(h.s, h.t);
  out.error = std::max(0.0, h.value - r.lowerBound);
  const Eigen::Vector3d away = q_M - h.point;
  const double d = away.norm();
  // Sum of the normals of the tied candidates at the same place (an edge or corner sees every face meeting
  // there); ties elsewhere (the centre of a sphere) do not take part.
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (const nurbs::PatchHit& t : r.ties)
    if ((t.point - h.point).norm() <= kRelativeTie * size) normal += normalAt(t);
  if (!(normal.norm() > 1e-6)) normal = normalAt(h);
  normal.normalize();
  if (d <= 4 * std::numeric_limits<double>::epsilon() * (q_M.norm() + size)) {  // on the surface
    out.signedDistance = d;
    out.normal = normal;
    return out;
  }
  const bool inside = solid_ && away.dot(normal) < 0;
  out.signedDistance = inside ? -d : d;
  out.normal = inside ? Eigen::Vector3d(-away / d) : Eigen::Vector3d(away / d);
  return out;
}

Eigen::Vector3d NurbsModel::support(const Eigen::Vector3d& dir_M) const {
  const double n = dir_M.norm();
  if (!(n > 0)) return forest_->roots.front()->corners[0];
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
  return forest_->bytes.load() + roots;
}

std::vector<StructureReport> NurbsModel::structures() const {
  return {{"patch-tree", true, patchTreeBytes()}, standIns_->report()};
}

StandIn NurbsModel::atDetail(double maxDeviation) const {
  lod::checkLevel(maxDeviation);
  if (maxDeviation == 0) return StandIn{this, 0.0};
  return standIns_->get(*this, maxDeviation, [this](double level) { return lod::tessellate(*this, level); });
}

std::size_t NurbsModel::memoryBytes() const {
  std::size_t bytes = sizeof(*this) + patchTreeBytes() + standIns_->report().bytes;
  for (const NurbsSurface& s : surfaces_)
    bytes += sizeof(s) + (s.knotsU().size() + s.knotsV().size()) * sizeof(double) +
             static_cast<std::size_t>(s.countU() * s.countV()) * sizeof(Eigen::Vector4d);
  for (const RationalBezierPatch& p : patches_) bytes += sizeof(p) + 2 * p.net.size() * sizeof(Eigen::Vector4d);
  return bytes;
}

}  // namespace unidist
