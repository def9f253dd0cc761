// Global minimisation over the patch forest of a NURBS model, shared by the point query (minimise |S − q|)
// and the support map (minimise −d·S). Best-first on a proved lower bound per node; a node survives only
// when it can hold an interior critical point (the objective's direction is parallel to its normal cone) or
// an edge critical point on a patch edge it touches (the direction is orthogonal to the tangent cone along
// that edge); patch corners are evaluated as nodes appear. Survivors that are small and nearly flat are
// closed when their gradient proves they hold no minimum of their own, else polished by box-constrained Newton
// on the whole patch, and split when the run leaves them. Internal.
#pragma once

#include "nurbs/patch_tree.h"
#include "nurbs/start_set.h"

#include <limits>
#include <vector>

namespace unidist::nurbs {

struct PatchHit;

/// What is minimised.
class Objective {
 public:
  virtual ~Objective() = default;
  virtual double value(const Eigen::Vector3d& p) const = 0;
  /// A cheaper function increasing with value (the search ranks candidates with it; no square root).
  virtual double rank(const Eigen::Vector3d& p) const { return value(p); }
  /// rank of a value (value → rank is increasing).
  virtual double rankOf(double value) const { return value; }
  /// Proved: value >= this on the node's subpatch.
  virtual double lowerBound(const PatchNode& n) const = 0;
  /// lowerBound, or a cheaper proved bound when that one is already >= `enough` (the node is then of no use).
  virtual double lowerBound(const PatchNode& n, double enough) const {
    (void)enough;
    return lowerBound(n);
  }
  /// A proved lower bound on the least curvature of the objective's smooth form over the node (its local
  /// parameters): positive where it is proved convex there, else zero.
  virtual double curvature(const PatchNode& n, const PatchForest& forest) const {
    (void)n, (void)forest;
    return 0;
  }
  /// Proved, given curvature(n) > 0: value >= this on the node, from a point h of it where a Newton run ended.
  virtual double basinBound(const PatchNode& n, const PatchHit& h, double curvature) const {
    (void)n, (void)h, (void)curvature;
    return -std::numeric_limits<double>::infinity();
  }
  /// Proved: value >= this on the node, where h, a point of it on a patch edge where a Newton run ended, is shown
  /// to hold the node's least value along that edge; minus infinity where not proved.
  virtual double edgeBound(const PatchNode& n, const PatchForest& forest, const PatchHit& h) const {
    (void)n, (void)forest, (void)h;
    return -std::numeric_limits<double>::infinity();
  }
  /// The tightest proved bound to be had, dearest: asked only of a piece closed without a proof that a Newton run
  /// found its minimum, whose bound then limits the search's. `enough`: a bound that would not limit it.
  virtual double closingBound(const PatchNode& n, double enough) const {
    (void)enough;
    return tightLowerBound(n);
  }
  /// The same, for a try that may well fail: no dearer than a few dozen subdivisions.
  virtual double quickClosingBound(const PatchNode& n, double enough) const { return closingBound(n, enough); }
  /// Whether curvature/basinBound or edgeBound can ever prove a piece: where not, the search takes a small flat
  /// piece a Newton run ended in to hold that one minimum, instead of splitting it for a proof that cannot come.
  virtual bool provesBasins() const { return false; }
  /// The least tolerance its proved bounds can honour where the objective is near `value`, on patches of at most
  /// `terms` control points (their rounding): the search never splits for less.
  virtual double resolution(double value, std::size_t terms) const {
    (void)value, (void)terms;
    return 0;
  }
  /// A tighter proved bound, dearer: asked only of a node the search would otherwise split.
  virtual double tightLowerBound(const PatchNode& n) const { return lowerBound(n); }
  /// Directions an interior critical point's normal must be parallel to (for the point query: q − S).
  virtual Cone criticalDirections(const BoundingSphere& b) const = 0;
  /// Gradient and Hessian (with respect to the local parameters) of a smooth function with the same minimisers.
  virtual void derivatives(const SurfaceDerivatives& d, Eigen::Vector2d& gradient, Eigen::Matrix2d& hessian) const = 0;
  /// A bound on the rounding error of each component of derivatives()'s gradient (infinite: none known).
  virtual double gradientError(const SurfaceDerivatives& d) const {
    (void)d;
    return std::numeric_limits<double>::infinity();
  }
  /// Size that makes a node "small" (leaf when its radius is below a fraction of it).
  virtual double leafScale(const BoundingSphere& b) const = 0;
  /// Proved: no point of the node is a local minimum over its patch, patch corners and points within
  /// `negligible` of a corner aside (gradient_sign.h). Asked of a small flat node before its Newton run.
  virtual bool provesNoMinimum(const PatchNode& n, const PatchForest& forest, double negligible) const = 0;
  /// rank() of every start sample, and per start node its lowerBound() where that may be below `below` (where
  /// not, any value >= below), into `out` (sized by the caller; start_set.h): one call for the whole set, which
  /// the point query makes a vectorised loop.
  virtual void startRanks(const StartSet& start, double* out) const;
  virtual void startBounds(const StartSet& start, double below, double* out) const;
};

/// Su x Sv normalised into `unit` where the surface is regular; false where it (nearly) vanishes (a pole).
inline bool unitNormal(const SurfaceDerivatives& d, Eigen::Vector3d& unit) {
  const Eigen::Vector3d n = d.du.cross(d.dv);
  const double scale = d.du.norm() * d.dv.norm();
  if (!(n.norm() > 1e-10 * scale && scale > 0)) return false;
  unit = n.normalized();
  return true;
}

/// A point of a patch found by the search.
struct PatchHit {
  int patch = -1;
  double s = 0, t = 0, value = 0;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  /// Unit Su x Sv there where a Newton run ended and the surface is regular (zero elsewhere: not computed).
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  /// Where a Newton run ended: the smooth function's gradient in the patch's local parameters, each component
  /// known to within gradientError (infinite elsewhere: not computed).
  Eigen::Vector2d gradient = Eigen::Vector2d::Zero();
  double gradientError = std::numeric_limits<double>::infinity();
};

struct SearchResult {
  PatchHit best;
  std::vector<PatchHit> ties;  ///< every hit within tieTolerance of the best (including it)
  int nodes = 0;
  bool exhausted = false;
  /// The objective's minimum is at least this, proved: best.value − tolerance, or less where a piece was closed
  /// without a proof that its run found its minimum (its closingBound), or when the budget ran out the lowest
  /// bound still open.
  double lowerBound = -std::numeric_limits<double>::infinity();
  /// Pieces closed by basinBound or edgeBound (a proof: the objective convex over them, or along the patch edge
  /// their least value is on).
  int convex = 0;
  /// Small flat pieces closed on a Newton run that ended inside them without a proof that it found their minimum
  /// (next to a pole, or after kCertSplits levels): their closingBound caps lowerBound.
  int premised = 0;
  /// Pieces closed on a Newton run without a proof that they hold no other minimum (see minimise()).
  int unproved = 0;
};

/// Global minimum of the objective over every patch, to `tolerance` (absolute). Patch `skip` is left out, or
/// every patch but `only` (-1 for none).
SearchResult minimise(const PatchForest& forest, const std::vector<RationalBezierPatch>& patches, const Objective& f,
                      double tolerance, double tieTolerance, int skip = -1, int only = -1);

/// A box of a patch's local parameters.
struct ParamBox {
  double s0 = 0, s1 = 1, t0 = 0, t1 = 1;
};

/// The patch's point at (s, t) with the objective's value and gradient there.
PatchHit pointAt(const RationalBezierPatch& patch, int index, const Objective& f, double s, double t);

/// How a Newton step is accepted: where it lowers the value, or also where it keeps the value within a few
/// ulps and halves the gradient (the last runs of a search: far from the surface the value is flat to rounding
/// near its minimum, and only the gradient shows the way; taken in every run it slowed the depth search 70×).
enum class Steps { Descent, AlongGradient };

/// Box-constrained Newton on patch from (s, t) (clamped into the box); returns the best point reached.
PatchHit polish(const RationalBezierPatch& patch, int index, const Objective& f, double s, double t,
                const ParamBox& box = {}, Steps steps = Steps::Descent);

}  // namespace unidist::nurbs
