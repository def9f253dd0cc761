// The subdivision tree of every Bézier patch of a NURBS model: per node a subpatch (homogeneous net cut by de
// Casteljau), a proved bounding ball and cones bounding the directions of Su, Sv and the normal Su x Sv.
// Children are made lazily; nodes down to kCachedDepth are kept (std::call_once per node, so concurrent
// queries build each node once), deeper nodes belong to the caller's scratch arena. Internal.
#pragma once

#include "unidist/nurbs.h"

#include <array>
#include <atomic>
#include <memory>
#include <mutex>
#include <unordered_map>
#include <utility>
#include <vector>

namespace unidist::nurbs {

struct CurvatureForm;
struct GradientForm;
struct StartSet;

/// A cone of directions {axis, half-angle}; `all` means every direction (no bound). The cosine and sine of the
/// angle are kept so that the tests below need no trigonometry; they may leave out the angle's rounding slack,
/// which the tests allow for. Make cones with makeCone.
struct Cone {
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  double angle = 0;
  bool all = true;
  double cosine = 1, sine = 0;
};

/// The cone {axis (unit), angle}.
Cone makeCone(const Eigen::Vector3d& axis, double angle);

/// Smallest-ish cone containing every non-zero vector given (incremental growth); all when some angle reaches π/2
/// (a wider cone would not contain the non-negative combinations of its vectors).
Cone coneOfVectors(const std::vector<Eigen::Vector3d>& vectors);
/// Cone of the cross products v x w, v in cu, w in cv (algorithms.md §1.2, corrected formula).
Cone crossCone(const Cone& cu, const Cone& cv);
/// Cone of the directions from the points of a ball (c, r) to q.
Cone coneTowards(const Eigen::Vector3d& q, const Eigen::Vector3d& c, double r);
/// Some direction of a is within the cone b or its negation.
bool meetsEitherWay(const Cone& a, const Cone& b);
/// Some v in a and w in b with v·w = 0.
bool canBeOrthogonal(const Cone& a, const Cone& b);

/// Proved ball around the Euclidean control points (convex hull property), widened for rounding.
BoundingSphere ballOfNet(const std::vector<Eigen::Vector4d>& net);
/// The same for Euclidean points.
BoundingSphere ballOfPoints(const std::vector<Eigen::Vector3d>& points);
/// Bernstein coefficients of the numerator X_u W − X W_u of Su divided by the degree p (degree (2p − 1, 2q),
/// u-major), computed from the Euclidean points so that equal points give exactly zero. With transpose, those
/// of Sv with u and v swapped (v-major).
std::vector<Eigen::Vector3d> derivativeCoefficients(const RationalBezierPatch& patch, bool transpose);
/// Cones of Su and Sv over the whole patch, from the Bernstein coefficients of the rational derivative numerators.
void tangentCones(const RationalBezierPatch& patch, Cone& cu, Cone& cv);
/// The part of the patch over [a, b] of local parameter s (direction 0) or t (direction 1), by de Casteljau.
RationalBezierPatch restrict(const RationalBezierPatch& patch, int direction, double a, double b);
/// The subpatch over [s0,s1] x [t0,t1] of the local parameters.
RationalBezierPatch subpatch(const RationalBezierPatch& patch, double s0, double s1, double t0, double t1);

/// A box in an orthonormal frame around the ball's centre c holding the control points (so the subpatch),
/// widened for rounding: {x : lo <= axes·(x − c) <= hi}. Across a nearly flat node (the frame's third axis
/// is its normal) it is as thin as the node is curved, where the ball is as thick as the node is wide.
struct FrameBox {
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  // rows: the frame's unit vectors
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero();
};

constexpr int kFarFromPole = 1 << 20;

struct PatchNode {
  RationalBezierPatch net;             // the subpatch, local parameters of its own
  std::vector<Eigen::Vector3d> points;  // its Euclidean control points: their hull holds it (positive weights)
  int patch = 0, depth = 0;
  double s0 = 0, s1 = 1, t0 = 0, t1 = 1;  // its box in the patch's local parameters
  bool kept = false;  // owned by the forest (a root or a cached child), not by one query's arena
  int fromPole = kFarFromPole;  // levels below the last strip along a pole it descends from (0: a strip itself)
  /// It touches a patch edge collapsed to a point (PatchForest::children splits it as a strip).
  bool onPole() const { return fromPole == 0; }
  BoundingSphere ball;
  FrameBox box;
  Cone cu, cv, normal;
  std::array<Eigen::Vector3d, 4> corners;  // surface points at (s0,t0), (s1,t0), (s0,t1), (s1,t1)

  mutable std::once_flag childrenOnce;
  mutable std::array<std::unique_ptr<PatchNode>, 4> cached;
  mutable std::once_flag gradientOnce;  // the gradient's Bernstein form, made when first asked (gradient_sign.h)
  mutable std::shared_ptr<const GradientForm> gradient;
  mutable std::once_flag curvatureOnce;  // the Hessian's q-independent Bernstein forms, likewise (point_convexity.h)
  mutable std::shared_ptr<const CurvatureForm> curvature;
};

constexpr int kCachedDepth = 7;
/// Along a pole the chain of strips (one node per level, with its three neighbours) is kept deeper: the proofs
/// next to a pole need the forms of pieces far smaller than the cached depth's.
constexpr int kPoleCachedDepth = 20;

/// A value per node made once during one search (a separator's certified extreme), looked up by the node.
/// A few entries are scanned (a search usually certifies tens of nodes); past that they are hashed, as a search
/// along a continuum of minima certifies thousands and a scan would make it quadratic.
class NodeMemo {
 public:
  template <class Make>
  double get(const PatchNode& node, Make&& make) {
    if (const double* known = find(node)) return *known;
    const double value = make();
    set(node, value);
    return value;
  }

  /// The node's value, or none where it has none yet (valid until the next value is recorded).
  const double* find(const PatchNode& node) const {
    if (hashed_.empty()) {
      for (const auto& [key, value] : entries_)
        if (key == &node) return &value;
      return nullptr;
    }
    const auto it = hashed_.find(&node);
    return it == hashed_.end() ? nullptr : &it->second;
  }

  /// Records the value of a node that has none yet.
  void set(const PatchNode& node, double value) {
    if (entries_.size() < kScanned) {
      entries_.emplace_back(&node, value);
    } else {
      if (hashed_.empty()) hashed_.insert(entries_.begin(), entries_.end());
      hashed_.emplace(&node, value);
    }
  }

 private:
  static constexpr std::size_t kScanned = 32;
  std::vector<std::pair<const PatchNode*, double>> entries_;
  std::unordered_map<const PatchNode*, double> hashed_;
};

/// Proved: |q − x| >= this for every point x of the node's subpatch (the distance from q to its frame box).
double boxDistance(const PatchNode& n, const Eigen::Vector3d& q);

/// Can the node hold a point where some direction of `towards` is normal to the surface (an interior critical
/// point), or orthogonal to the tangent along a patch edge the node touches (an edge critical point)? With
/// `corners`, a node holding a patch corner always can (a corner extremum obeys no equation).
bool mayHoldCritical(const PatchNode& n, const Cone& towards, bool corners);


struct PatchForest {
  std::vector<std::unique_ptr<PatchNode>> roots;
  std::size_t maxTerms = 0;  // the most control points of any patch
  /// The distinct points patch edges collapse to, each with the edges (patch, 0..3 as below) meeting there.
  struct Pole {
    Eigen::Vector3d point;
    std::vector<std::pair<int, int>> edges;
  };
  std::vector<Pole> poles;
  /// Per patch, for its edges s = 0, s = 1, t = 0, t = 1: the index in `poles` of the point it collapses to, or
  /// −1 where it is not collapsed.
  std::vector<std::array<int, 4>> poleOfEdge;
  /// The patches' corners, each distinct point once (patches meet at their corners: a torus's 64 are 16 points),
  /// with its first occurrence in (root, corner) order, sorted by that.
  struct Corner {
    Eigen::Vector3d point;
    int root, corner;
  };
  std::vector<Corner> distinctCorners;
  mutable std::atomic<std::size_t> nodes{0}, bytes{0};
  mutable std::once_flag startOnce;  // the search's starting cut (start_set.h), made on first use
  mutable std::shared_ptr<const StartSet> start;

  explicit PatchForest(const std::vector<RationalBezierPatch>& patches);
  /// The four children of n: its quadrants in u-major order; a node along a collapsed edge (a pole) is cut into
  /// the quarter of it along the pole (a strip spanning its whole width, the next strip of the pole's chain),
  /// the next quarter, and the far half's two halves, so that only one node per level touches the pole where
  /// quadrants would double them. Cached ones are built once; deeper ones go to arena.
  std::array<const PatchNode*, 4> children(const PatchNode& n,
                                           std::vector<std::unique_ptr<PatchNode>>& arena) const;
  /// Are n's children kept by the forest (cached) rather than made per query?
  static bool keepsChildren(const PatchNode& n) {
    return n.depth < kCachedDepth || (n.onPole() && n.depth < kPoleCachedDepth);
  }
};

/// A node for `net` covering [s0,s1] x [t0,t1] of patch `patch`: ball, cones and corners computed.
std::unique_ptr<PatchNode> makeNode(RationalBezierPatch net, int patch, int depth, double s0, double s1, double t0,
                                    double t1);

}  // namespace unidist::nurbs
