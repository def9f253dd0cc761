// A stateful tracker of the local minima of distance between two models, for 6-DOF haptic rendering at servo
// rate (≈1 kHz): the set of local minima within a cutoff is kept from one relative pose to the next and updated
// locally, a global pass (unidist::contacts) supplies minima that appeared, and a penalty model turns the tracked
// minima into a force and a torque on A (Johnson's 6-DOF rendering, ../shared/docs/algorithms.md §6).
//
// Local update of one minimum, from its previous witness points and features (cost independent of model size):
//  * NURBS – NURBS: Newton on the four parameters (u_A, v_A, u_B, v_B) of the extremal system written so that
//    it stays regular through touching: B's point on A's normal line, A's normal normal to B
//    ((P_B − P_A)·A_u = (P_B − P_A)·A_v = 0, n_A·B_s = n_A·B_t = 0). Its roots are the separated minima and the
//    penetration extrema alike, so one branch is followed into and out of contact; periodic parameters (a
//    closed surface's seam) are wrapped.
//  * mesh – mesh apart: Johnson's local descent over triangle pairs (a triangle's ring: the triangles sharing a
//    vertex with it; exact triangle–triangle distances), then the alternation below to settle signs and normal.
//  * every other pair apart: alternating local projections (Johnson & Cohen's point–model alternation,
//    accelerated by Anderson mixing: plain alternation crawls where the gap is small beside the curvature
//    radii), each projection local — a walk over a mesh's triangle neighbours from the cached triangle, a point
//    Newton on a NURBS surface from the cached (u, v), the exact closest point of a primitive or a cloud.
//  * overlapping: two meshes — the locally deepest vertex of each inside the other, over the vertex graph (what
//    contacts() reports), or the local penetration extremum where edges cross with no vertex inside; two other
//    solids — the penetration extremum, as the closest pair of the same solids with B lifted out along the
//    contact normal (exact for a translation; the lift direction is re-read until it settles); a model without
//    an inside (cloud, open surface) — its locally deepest point in the solid, by support probes.
// A NURBS pair that leaves Newton's reach (a pole, an open surface's boundary, a branch that ended) falls back to
// the alternation; minima that converge onto each other (both points within the merge distance) are merged,
// keeping the oldest; minima beyond cutoff + 2·guard are dropped, and so is a minimum that turns penetrating
// while neither of its points is inside the other solid (a locally closest feature's sign is right only for the
// globally closest one: a walk that ends on the far side of a slab reads the slab's thickness as a depth).
//
// Global pass policy. A global pass runs unidist::contacts() with the margin grown to cutoff + 2·guard. While the
// relative pose has moved less than `guard` since the pose the pass ran at (largest displacement of any point of
// the smaller model), every pair of points now within the cutoff was within cutoff + 2·guard then — the
// argument of ContactCache (contact_manifold.h) — so the pass saw its region, and the local updates keep it.
// A pass is therefore started when (a) there is none yet, (b) the relative motion since the last pass exceeds
// the guard, or (c) `globalPeriod` updates have passed (a cap: minima can also be born without motion of their
// region beyond the guard, where two curvatures meet). With GlobalPassMode::Background the pass runs on its own
// thread (as in the dissertation: the servo loop never waits for it; the first update alone is synchronous) and
// its minima are merged at the first update after it finished, after a local update to the pose of that update.
// With GlobalPassMode::Inline it runs inside update() (deterministic: tests; the cold-query cost then shows up in
// the update times of those steps). In background mode "the period" is the pass's own duration plus the
// trigger: a minimum born meanwhile is missed until the pass started after its birth is merged.
// Discrete models (clouds, facets) gain minima by birth all the time (a point becoming the nearest, a vertex
// passing an edge): those are found by the next pass, not by the local updates.
//
// Forces (on A, world frame): per reported minimum i with distance d_i < d0 = penaltyDistance, its push
// p_i = max(0, k·(d0 − d_i) − c·ḋ_i) (ḋ_i the change of d_i since the previous update divided by timeStep; 0 for
// a new minimum and for a change larger than the pair's relative motion, a jump onto another branch), and minima pushing the same way share it: f_i = p_i² / Σ_j w_ij·p_j along −n_i (n_i points from
// A to B: A is pushed away), w_ij = 1 for normals within 15°, 0 beyond 45°, smooth between. A flat contact that a
// faceted surface splits into one, two or five minima thus pushes as one (n equal pushes give one p), while
// contacts on different sides (a groove's two walls) add; torque Σ (p_A,i − r) × F_i about the
// reference point r (given in A's frame). A minimum enters and leaves at the cutoff ≥ d0, where its force is 0,
// so the force stays continuous as minima come and go.
//
// Thread-safety: one Tracker per pair, update() is not const and not for concurrent calls; the models are
// shared read-only (their own queries are thread-safe) and kept alive by the tracker.
#pragma once

#include "unidist/model.h"
#include "unidist/query_options.h"

#include <limits>
#include <memory>
#include <vector>

namespace unidist {

enum class GlobalPassMode {
  Inline,      ///< inside update(), deterministic
  Background,  ///< on a worker thread; merged at the first update after it finished
};

/// The dial (QueryOptions): tolerance < 0 → 1e-6 × the smaller bounding-box diagonal of the pair (for the
/// local updates and the global passes alike; haptics needs no more), 0 → 1e-12 × that diagonal. detailA/B: the
/// tracker follows the models' stand-ins at those levels of detail (Model::atDetail), chosen once at construction.
struct TrackerOptions : QueryOptions {
  double cutoff = -1;           ///< report minima with distance <= cutoff; < 0 → 2% of the smaller diagonal
  double guard = -1;            ///< relative motion allowed between global passes; < 0 → cutoff
  int globalPeriod = 100;       ///< at most this many updates between global passes (> 0)
  GlobalPassMode globalPass = GlobalPassMode::Background;
  double stiffness = 1;         ///< k (force per unit length), >= 0
  double damping = 0;           ///< c (force per unit speed), >= 0
  double penaltyDistance = -1;  ///< d0 <= cutoff; < 0 → cutoff (the force starts where a minimum is reported)
  double timeStep = 1e-3;       ///< seconds between updates (for the damping), > 0
  Eigen::Vector3d referencePoint_A = Eigen::Vector3d::Zero();  ///< torque reference, A's frame
  int maxLocalIterations = 30;  ///< per minimum and update (Newton steps, alternations, descent steps)
};

/// One tracked local minimum, world frame, in the conventions of unidist::Contact (pointB − pointA =
/// distance · normal, normal from A toward B, distance < 0 when penetrating).
struct TrackedMinimum {
  Eigen::Vector3d pointA = Eigen::Vector3d::Zero(), pointB = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double distance = 0;
  /// The models' features (mesh triangle, cloud point, NURBS surface index, primitive feature) and surface
  /// parameters (NURBS (u, v); mesh barycentric (b1, b2); zero elsewhere).
  int featureA = 0, featureB = 0;
  Eigen::Vector2d paramA = Eigen::Vector2d::Zero(), paramB = Eigen::Vector2d::Zero();
  long age = 0;      ///< updates since a global pass found it
  long id = 0;       ///< stable while it is tracked
  double force = 0;  ///< magnitude of its penalty force
};

struct TrackerUpdate {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   ///< on A, world
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();  ///< on A about the reference point, world
  int minima = 0;                 ///< reported (within the cutoff)
  double deepest = std::numeric_limits<double>::infinity();  ///< smallest reported distance (inf: none)
  bool globalPassStarted = false; ///< this update started a global pass (inline: and ran it)
  bool globalPassMerged = false;  ///< this update merged a global pass's minima
  int added = 0, dropped = 0, merged = 0;
};

struct TrackerCounters {
  long updates = 0, globalPasses = 0;
  long newtonIterations = 0;  ///< NURBS pair and point Newton steps
  long localSteps = 0;        ///< projections, walk and descent steps
  long fallbacks = 0;         ///< local updates that fell back to a global point query
  long falseOverlaps = 0;     ///< minima dropped for a penetration sign their points' inside tests deny
};

class Tracker {
 public:
  /// Throws InputError for missing models, a pair of half-spaces or bad options.
  Tracker(std::shared_ptr<const Model> a, std::shared_ptr<const Model> b, const TrackerOptions& options = {});
  ~Tracker();  // waits for a pass in flight
  Tracker(const Tracker&) = delete;
  Tracker& operator=(const Tracker&) = delete;

  /// Moves the pair to the new poses and returns the force on A. Throws InputError for a non-finite pose.
  const TrackerUpdate& update(const Eigen::Isometry3d& X_WA, const Eigen::Isometry3d& X_WB);
  /// The minima within the cutoff after the last update, deepest first.
  const std::vector<TrackedMinimum>& minima() const;
  const TrackerUpdate& last() const;
  const TrackerCounters& counters() const;
  /// The options with every default resolved (tolerance, cutoff, guard, penaltyDistance).
  const TrackerOptions& options() const;
  /// Background mode: blocks until the pass in flight (if any) has finished; the next update merges it.
  void waitForGlobalPass();
  /// Forgets every minimum; the next update runs a synchronous global pass.
  void reset();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace unidist
