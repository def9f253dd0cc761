// Local point projections (tracking/local_surface.h): the mesh walk, the NURBS point Newton, and the exact query
// for everything else.
#include "tracking/local_surface.h"

#include "mesh/point_triangle.h"
#include "tracking/nurbs_params.h"
#include "unidist/mesh.h"
#include "unidist/nurbs.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace unidist::tracking {
namespace {

void addOnce(std::vector<int>& out, int x) {
  if (x >= 0 && std::find(out.begin(), out.end(), x) == out.end()) out.push_back(x);
}

/// A walk longer than this means the point moved far from its last triangle (a jump, not servo-rate motion):
/// the hierarchy answers faster than more steps.
constexpr int kMaxWalkSteps = 48;
constexpr int kMaxPointNewton = 16;

/// Primitives and point clouds: their exact closest point is already cheap (closed forms, the point tree).
class ExactSurface final : public LocalSurface {
 public:
  explicit ExactSurface(const Model& m) : LocalSurface(m) {}
  SurfacePoint project(const Eigen::Vector3d& q, Hint& hint, Work& work) const override {
    ++work.steps;
    const SurfacePoint s = model_->closestPoint(q);
    hint = hintOf(s);
    return s;
  }
};

/// Triangle mesh: from the hint's triangle, move to the nearest triangle among those sharing a vertex with the
/// current one until none is nearer (the one-ring covers every triangle the closest point can slide onto
/// across an edge or a vertex). Signed by the mesh itself (TriangleMesh::surfacePointOn).
class MeshSurface final : public LocalSurface {
 public:
  explicit MeshSurface(const TriangleMesh& m) : LocalSurface(m), mesh_(m) {
    const auto& tris = m.triangles();
    start_.assign(m.vertices().size() + 1, 0);
    for (const auto& t : tris)
      for (std::uint32_t v : t) ++start_[v + 1];
    for (std::size_t i = 1; i < start_.size(); ++i) start_[i] += start_[i - 1];
    fan_.resize(start_.back());
    std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t t = 0; t < tris.size(); ++t)
      for (std::uint32_t v : tris[t]) fan_[fill[v]++] = static_cast<std::uint32_t>(t);
  }

  SurfacePoint project(const Eigen::Vector3d& q, Hint& hint, Work& work) const override {
    const int count = static_cast<int>(mesh_.triangles().size());
    int t = hint.feature >= 0 && hint.feature < count ? hint.feature : 0;
    mesh::TriangleClosest best = closest(q, t);
    for (int step = 0;; ++step) {
      if (step == kMaxWalkSteps) {
        ++work.fallbacks;
        const SurfacePoint s = mesh_.closestPoint(q);
        hint = hintOf(s);
        return s;
      }
      ++work.steps;
      int next = t;
      for (std::uint32_t v : mesh_.triangles()[static_cast<std::size_t>(t)])
        for (std::uint32_t k = start_[v]; k < start_[v + 1]; ++k) {
          const int u = static_cast<int>(fan_[k]);
          if (u == t) continue;
          const mesh::TriangleClosest c = closest(q, u);
          if (c.squaredDistance < best.squaredDistance) best = c, next = u;
        }
      if (next == t) break;
      t = next;
    }
    hint = {t, {best.b1, best.b2}};
    return mesh_.surfacePointOn(q, t, best);
  }

  bool hasVertexGraph() const override { return true; }
  int nearestVertex(const Hint& h, const Eigen::Vector3d& p) const override {
    const auto& tri = mesh_.triangles()[static_cast<std::size_t>(h.feature)];
    const auto& x = mesh_.vertices();
    std::uint32_t best = tri[0];
    for (std::uint32_t v : tri)
      if ((x[v] - p).squaredNorm() < (x[best] - p).squaredNorm()) best = v;
    return static_cast<int>(best);
  }
  void vertexNeighbours(int v, std::vector<int>& out) const override {
    out.clear();
    const auto uv = static_cast<std::uint32_t>(v);
    for (std::uint32_t k = start_[uv]; k < start_[uv + 1]; ++k)
      for (std::uint32_t w : mesh_.triangles()[fan_[k]])
        addOnce(out, w == uv ? -1 : static_cast<int>(w));
  }
  Eigen::Vector3d vertex(int v) const override { return mesh_.vertices()[static_cast<std::size_t>(v)]; }
  const TriangleMesh* mesh() const override { return &mesh_; }
  void triangleRing(int t, std::vector<int>& out) const override {
    out.clear();
    out.push_back(t);
    for (std::uint32_t v : mesh_.triangles()[static_cast<std::size_t>(t)])
      for (std::uint32_t k = start_[v]; k < start_[v + 1]; ++k)
        addOnce(out, static_cast<int>(fan_[k]));
  }
  Hint vertexHint(int v) const override {
    const std::uint32_t t = fan_[start_[static_cast<std::size_t>(v)]];
    const auto& tri = mesh_.triangles()[t];
    Eigen::Vector2d b = Eigen::Vector2d::Zero();
    if (tri[1] == static_cast<std::uint32_t>(v)) b.x() = 1;
    if (tri[2] == static_cast<std::uint32_t>(v)) b.y() = 1;
    return {static_cast<int>(t), b};
  }

 private:
  mesh::TriangleClosest closest(const Eigen::Vector3d& q, int t) const {
    const auto& tri = mesh_.triangles()[static_cast<std::size_t>(t)];
    const auto& v = mesh_.vertices();
    return mesh::closestOnTriangle(q, v[tri[0]], v[tri[1]], v[tri[2]], mesh_.faceNormal(t));
  }

  const TriangleMesh& mesh_;
  std::vector<std::uint32_t> start_, fan_;  // vertex → triangles (CSR)
};

/// NURBS: Newton on ½|S(u, v) − q|² over the hint's surface, periodic parameters wrapped (a point moves across a
/// closed surface's seam), Levenberg damping where the Hessian is not positive definite, a step kept only when
/// the distance decreases. The exact search answers where Newton cannot: a degenerate
/// parametrisation (a pole), a point leaving an open surface's domain, or no convergence.
class NurbsLocalSurface final : public LocalSurface {
 public:
  explicit NurbsLocalSurface(const NurbsModel& m) : LocalSurface(m), nurbs_(m), params_(m) {}

  SurfacePoint project(const Eigen::Vector3d& q, Hint& hint, Work& work) const override {
    const int count = static_cast<int>(nurbs_.surfaces().size());
    if (hint.feature >= 0 && hint.feature < count) {
      SurfacePoint s;
      if (newton(q, hint, work, s)) return s;
    }
    ++work.fallbacks;
    const SurfacePoint s = nurbs_.closestPoint(q);
    hint = hintOf(s);
    return s;
  }

 private:
  bool newton(const Eigen::Vector3d& q, Hint& hint, Work& work, SurfacePoint& out) const {
    const NurbsSurface& surf = nurbs_.surfaces()[static_cast<std::size_t>(hint.feature)];
    const SurfaceParams& sp = params_.of(hint.feature);
    Eigen::Vector2d x = sp.wrap(hint.param);
    SurfaceDerivatives d = surf.derivatives(x.x(), x.y());
    double f = (d.point - q).squaredNorm();
    bool converged = false;
    for (int it = 0; it < kMaxPointNewton && !converged; ++it) {
      ++work.newton;
      const Eigen::Vector3d r = d.point - q;
      const Eigen::Vector2d g(r.dot(d.du), r.dot(d.dv));
      Eigen::Matrix2d H;
      H << d.du.dot(d.du) + r.dot(d.duu), d.du.dot(d.dv) + r.dot(d.duv), d.du.dot(d.dv) + r.dot(d.duv),
          d.dv.dot(d.dv) + r.dot(d.dvv);
      const double metric = d.du.squaredNorm() + d.dv.squaredNorm();
      if (!(d.du.cross(d.dv).norm() > 1e-10 * metric) || !(metric > 0)) return false;  // degenerate: a pole
      double lambda = 0;
      bool stepped = false;
      for (int tries = 0; tries < 8; ++tries) {
        Eigen::Matrix2d Hd = H;
        Hd.diagonal().array() += lambda;
        const Eigen::LLT<Eigen::Matrix2d> llt(Hd);
        if (llt.info() != Eigen::Success) {
          lambda = std::max(2 * lambda, 1e-3 * metric);
          continue;
        }
        const Eigen::Vector2d step = -llt.solve(g);
        Eigen::Vector2d y = x + step;
        if (!sp.inside(y)) return false;  // leaving an open domain: the boundary needs the exact search
        y = sp.wrap(y);
        const SurfaceDerivatives e = surf.derivatives(y.x(), y.y());
        const double fy = (e.point - q).squaredNorm();
        if (fy <= f) {
          const double moved = (e.point - d.point).norm();
          converged = moved <= 1e-13 * (1 + q.cwiseAbs().maxCoeff()) + 1e-9 * std::sqrt(f) ||
                      step.norm() <= 1e-14 * sp.scale();
          x = y, d = e, f = fy, stepped = true;
          break;
        }
        lambda = std::max(4 * lambda, 1e-3 * metric);
      }
      if (!stepped) converged = true;  // no step decreases the distance: at the minimum to rounding
    }
    if (!converged) return false;
    hint.param = x;
    out.point = d.point;
    out.feature = hint.feature;
    out.param = x;
    const Eigen::Vector3d gap = q - d.point;
    const double dist = gap.norm();
    Eigen::Vector3d n = d.du.cross(d.dv).normalized() * static_cast<double>(nurbs_.orientation());
    if (!nurbs_.isSolid()) {
      out.signedDistance = dist;
      out.normal = dist > 0 ? Eigen::Vector3d(gap / dist) : n;
      return true;
    }
    const bool in = n.dot(gap) < 0;
    out.signedDistance = in ? -dist : dist;
    out.normal = dist > 0 ? Eigen::Vector3d((in ? -1.0 : 1.0) * gap / dist) : n;
    return true;
  }

  const NurbsModel& nurbs_;
  ModelParams params_;
};

}  // namespace

std::unique_ptr<LocalSurface> LocalSurface::make(const Model& m) {
  if (const auto* mesh = dynamic_cast<const TriangleMesh*>(&m)) return std::make_unique<MeshSurface>(*mesh);
  if (const auto* nurbs = dynamic_cast<const NurbsModel*>(&m)) return std::make_unique<NurbsLocalSurface>(*nurbs);
  return std::make_unique<ExactSurface>(m);
}

}  // namespace unidist::tracking
