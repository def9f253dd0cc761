// NURBS models: rational B-spline surfaces of any degree (up to kMaxNurbsDegree), several per model, with an
// exact point query that is global (never a local minimum reported as the global one).
//
// NurbsSurface (validated at construction, InputError naming the problem otherwise):
//  * degrees p, q >= 1 and <= kMaxNurbsDegree; an nu x nv control net with nu >= p + 1, nv >= q + 1, every
//    row the same length; control points (x, y, z, w): x, y, z Euclidean (not weight-multiplied) and finite,
//    w finite and > 0;
//  * full knot vectors: length nu + p + 1 (resp. nv + q + 1), finite, non-decreasing, parameter domain
//    [t_p, t_nu] of non-zero length. Unclamped vectors are accepted (the domain is still [t_p, t_nu]).
//  * evaluation: homogeneous B-spline sum, then the rational quotient rule for first and second derivatives.
//  * bezierPatches(): Boehm knot insertion until every knot of the domain has multiplicity p (resp. q), then one
//    rational Bézier patch per non-empty knot rectangle (exactly the same surface).
//
// NurbsModel (a Model of type Nurbs):
//  * solid = what the file says; a solid must be closed: every point of every non-degenerate Bézier patch
//    edge (sampled) lies within 1e-9 x the bounding-box diagonal of another patch (poles — edges collapsed to
//    a point — and seams are allowed), else InputError. Outward orientation: Su x Sv, unless the enclosed
//    volume computed with that orientation is negative, in which case every normal is flipped.
//  * closestPoint(q): best-first search over a subdivision tree of every Bézier patch (de Casteljau on the
//    homogeneous net). A subpatch is kept only when (a) its proved bounding ball can still beat the best
//    distance, and (b) it can hold a critical point: q − S can be parallel to its normal cone (interior), or
//    orthogonal to its tangent cone along a patch edge it touches (edge extremum); corners are evaluated
//    as they appear. Survivors that are small and nearly flat (normal cone under 0.5 rad, radius under half
//    of max(distance to q, 2% of the model size)) are polished by a box-constrained Newton iteration on the
//    whole patch (step accepted only when the distance decreases, gradient step in the surface metric where
//    the Hessian is not positive definite, active-set at the domain edges); a leaf that already holds the end
//    of an earlier Newton run is not run again. The search starts from Newton at the parameters of the
//    nearest control point (nodal mapping), only to have a good bound early. Budget: kNurbsSearchBudget
//    subpatches per query; at the exact centre of a sphere (every point equidistant) the answer is whichever
//    point was found first, with no NaN. A non-finite q is an InputError.
//    feature = surface index, param = (u, v) of that surface.
//    solid: signedDistance < 0 inside, decided by the outward normal(s) of the closest point(s) — the sum of
//    the unit normals of every candidate within 1e-9 x size of the best distance and of its point (so an edge
//    between two patches sees both faces); a degenerate normal (pole) is taken just inside the patch. normal = (q − p)/|q − p|
//    outside, (p − q)/|p − q| inside, the surface normal when q is on the surface; open: unsigned distance.
//  * localBounds(): the box of the Euclidean control points (exact for the sphere/torus/cylinder forms,
//    conservative for free-form patches).
//  * support(d): a surface point maximising d·p: the highest patch corner when it is as high as the highest
//    control point (exact, by the convex hull property: an axis direction on a revolved sphere or a box), else by
//    the same best-first search (bound: max d·P over the subpatch's control points; Newton on survivors), to
//    1e-13 x the model size.
//    Being on the surface, it is the support point of the convex hull of the surface within that tolerance.
//  * surfaceCells(): one cell per Bézier patch (face = patch index, parameter box [0,1]^2 of the patch);
//    splitCell quarters the box (the subpatch net is cut from the patch net directly). Centre and radius:
//    the proved ball of the subpatch's Euclidean control points (convex hull property: positive weights).
//  * The subdivision tree is built lazily and cached down to a fixed depth (thread-safe, std::call_once per
//    node); deeper nodes live only for the query that needs them.
#pragma once

#include "unidist/model.h"

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace unidist {

constexpr int kMaxNurbsDegree = 30;
constexpr int kNurbsSearchBudget = 20000;

namespace nurbs {
struct PatchForest;
struct PatchHit;
class PointCells;
}
namespace lod {
class StandInCache;
}

/// A point of a surface with its first and second partial derivatives.
struct SurfaceDerivatives {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d du = Eigen::Vector3d::Zero(), dv = Eigen::Vector3d::Zero();
  Eigen::Vector3d duu = Eigen::Vector3d::Zero(), duv = Eigen::Vector3d::Zero(), dvv = Eigen::Vector3d::Zero();
};

/// A rational Bézier patch in homogeneous form: net[i * (degreeV + 1) + j] = (w x, w y, w z, w) with u-index i.
/// Local parameters (s, t) in [0,1]^2 map to the NURBS parameters [u0,u1] x [v0,v1] it came from, through a
/// Möbius reparametrisation per direction: u = u0 + (u1 − u0)·σ(s), σ(s) = c·s / (1 − s + c·s), c = stretchU
/// (likewise v). NurbsSurface::bezierPatches() chooses c so that the corner weights are balanced (the same
/// surface: multiplying weight (i, j) by a^i·b^j only reparametrises it): weights spanning 1e-6…1e6 along a
/// direction crowd a patch's shape into a sliver of its parameter square, where midpoint subdivision never
/// catches up.
struct RationalBezierPatch {
  int degreeU = 0, degreeV = 0;
  std::vector<Eigen::Vector4d> net;
  double u0 = 0, u1 = 1, v0 = 0, v1 = 1;
  double stretchU = 1, stretchV = 1;

  /// The NURBS parameters of local (s, t).
  Eigen::Vector2d surfaceParam(double s, double t) const;

  const Eigen::Vector4d& at(int i, int j) const { return net[static_cast<std::size_t>(i * (degreeV + 1) + j)]; }
  Eigen::Vector4d& at(int i, int j) { return net[static_cast<std::size_t>(i * (degreeV + 1) + j)]; }
  /// Euclidean control point (i, j).
  Eigen::Vector3d point(int i, int j) const { return at(i, j).head<3>() / at(i, j)[3]; }
  /// Exact evaluation with derivatives with respect to the local parameters s, t.
  SurfaceDerivatives derivatives(double s, double t) const;
  Eigen::Vector3d evaluate(double s, double t) const;
};

class NurbsSurface {
 public:
  /// controlPoints[i][j] = (x, y, z, w), u-index i, v-index j. Throws InputError naming the problem.
  NurbsSurface(int degreeU, int degreeV, std::vector<double> knotsU, std::vector<double> knotsV,
               std::vector<std::vector<Eigen::Vector4d>> controlPoints);

  int degreeU() const { return p_; }
  int degreeV() const { return q_; }
  int countU() const { return nu_; }
  int countV() const { return nv_; }
  const std::vector<double>& knotsU() const { return knotsU_; }
  const std::vector<double>& knotsV() const { return knotsV_; }
  /// (x, y, z, w) of control point (i, j).
  Eigen::Vector4d controlPoint(int i, int j) const;
  double uMin() const { return knotsU_[static_cast<std::size_t>(p_)]; }
  double uMax() const { return knotsU_[static_cast<std::size_t>(nu_)]; }
  double vMin() const { return knotsV_[static_cast<std::size_t>(q_)]; }
  double vMax() const { return knotsV_[static_cast<std::size_t>(nv_)]; }

  /// Exact point and derivatives at (u, v) (clamped to the domain).
  SurfaceDerivatives derivatives(double u, double v) const;
  Eigen::Vector3d evaluate(double u, double v) const { return derivatives(u, v).point; }
  /// The same surface as rational Bézier patches (knot insertion), in u-major order.
  std::vector<RationalBezierPatch> bezierPatches() const;
  /// The part of the surface over [u0, u1] x [v0, v1] (knot insertion; parameters keep their values), as CAD
  /// files restrict a surface by a parameter range. Throws InputError unless the range is finite, non-empty and
  /// within the knot domain.
  NurbsSurface restricted(double u0, double u1, double v0, double v1) const;

 private:
  int p_, q_, nu_ = 0, nv_ = 0;
  std::vector<double> knotsU_, knotsV_;
  std::vector<Eigen::Vector4d> homogeneous_;  // (w x, w y, w z, w), index i * nv + j
};

class NurbsModel final : public Model {
 public:
  /// Throws InputError when there is no surface, or a solid is not closed (see the top of this file).
  NurbsModel(std::vector<NurbsSurface> surfaces, bool solid);
  ~NurbsModel() override;
  NurbsModel(const NurbsModel&) = delete;
  NurbsModel& operator=(const NurbsModel&) = delete;

  /// Prepares the point query for a model queried many times (a simulation's or a haptic loop's): the space
  /// around the model is cut into cells, each made by the first query landing in it and kept, in which a query
  /// is a short Newton run with a convexity proof instead of a search (docs/nurbs.md, "Prepared point
  /// queries"). About 3-5x faster once a region's cells exist (1.6 us on the exact torus); a query that makes
  /// a cell pays ~10-50 us, and the first queries of a model up to a few ms while the cells' node forms are
  /// made. Answers stay a function of the query point alone (a cell is made from its centre only), proved to
  /// the same tolerance. Call before sharing the model between threads; off by default.
  void preparePointQueries() { prepared_ = true; }

  ModelType type() const override { return ModelType::Nurbs; }
  SurfacePoint closestPoint(const Eigen::Vector3d& q_M) const override;
  Aabb localBounds() const override { return bounds_; }
  bool isSolid() const override { return solid_; }
  Eigen::Vector3d support(const Eigen::Vector3d& dir_M) const override;
  std::vector<SurfaceCell> surfaceCells() const override;
  void splitCell(const SurfaceCell& cell, std::vector<SurfaceCell>& out) const override;
  std::string describe() const override;
  std::size_t memoryBytes() const override;
  /// "patch-tree": the roots exist from construction (they bound the model); nodes below are refined, and kept
  /// down to a fixed depth, only where queries look. "level-of-detail": the stand-ins asked for (atDetail).
  std::vector<StructureReport> structures() const override;
  /// A triangle mesh proved within maxDeviation of the surfaces (a solid's is a closed mesh): a tensor grid per
  /// surface in its NURBS parameters, refined until a Bernstein bound on every cell's distance to its two
  /// triangles meets the level (docs/dial.md, "Level of detail"). The model itself when the level is finer
  /// than 1e-9 × its size, needs more than 4 million triangles, or a solid's surfaces meet along edges cut
  /// differently (the mesh would not be closed).
  StandIn atDetail(double maxDeviation) const override;

  const std::vector<NurbsSurface>& surfaces() const { return surfaces_; }
  const std::vector<RationalBezierPatch>& patches() const { return patches_; }
  /// Index of the surface patch k came from.
  int patchSurface(int k) const { return patchSurface_[static_cast<std::size_t>(k)]; }
  /// +1 when Su x Sv points outward, −1 when the model's normals are flipped (solids only; +1 for open).
  int orientation() const { return orientation_; }
  /// Whether surface s meets itself across its domain's edges in direction d (0: u, 1: v) — a revolved sphere's
  /// or torus's seam: the two opposite edges coincide pointwise (sampled, 1e-9 × size) and have length (a pole
  /// does not count). Found at construction.
  bool periodic(int s, int d) const { return periodic_[static_cast<std::size_t>(s)][static_cast<std::size_t>(d)]; }
  /// Outward unit normal of patch k at local (s, t); at a degenerate point (pole) the limit from inside the patch.
  Eigen::Vector3d patchNormal(int k, double s, double t) const;
  /// Whether the solid is proved to bound a convex body (Bernstein signs of its curvature and creases, one
  /// connected surface: core/src/nurbs/convexity_certificate.h). Then its penetration depth against another
  /// convex solid is a support-function minimum (GJK/EPA), not a search over translations. Decided on the
  /// first call (thread-safe; milliseconds for tens of patches); false for open surface sets. `why`, when
  /// given, receives what failed.
  bool provedConvex(std::string* why = nullptr) const;
  /// The subdivision tree (internal type, for tests and core/src).
  const nurbs::PatchForest& forest() const { return *forest_; }

 private:
  void checkClosed() const;
  std::array<bool, 2> findPeriodic(const NurbsSurface& s) const;
  double enclosedVolume() const;
  std::size_t patchTreeBytes() const;  // the cached subdivision tree so far
  Eigen::Vector3d normalAt(const nurbs::PatchHit& h) const;  // the search's normal where it has one
  // Whether q = p + away lies inside, p = h.point on a patch edge or corner: from every face meeting at p.
  bool insideAtBoundary(const nurbs::PatchHit& h, const Eigen::Vector3d& away, Eigen::Vector3d& normalSum) const;
  // A patch through a point of another's boundary, at its local (s, t) there.
  struct Incident {
    int patch;
    double s, t;
  };
  std::vector<Incident> incidentsAt(int k, const Eigen::Vector3d& x) const;  // every patch but k through x
  void findIncidents();

  std::vector<NurbsSurface> surfaces_;
  std::vector<RationalBezierPatch> patches_;
  std::vector<int> patchSurface_;
  bool solid_;
  int orientation_ = 1;
  Aabb bounds_;
  std::unique_ptr<nurbs::PatchForest> forest_;
  std::unique_ptr<lod::StandInCache> standIns_;
  std::unique_ptr<nurbs::PointCells> cells_;  // the point query's cells, made as queries reach them
  bool prepared_ = false;                      // whether the point query uses them
  std::vector<std::array<bool, 2>> periodic_;  // per surface, u and v
  // Solids: per patch, the other patches through its corners (s + 2t) and along its edges (4 + e: s = 0, s = 1,
  // t = 0, t = 1; at the edge's midpoint, kept only where one patch's whole edge matches it).
  std::vector<std::vector<Incident>> incidents_;
  struct Convexity;  // the convexity verdict, made on first use
  std::unique_ptr<Convexity> convexity_;
};

}  // namespace unidist
