// The local update of one tracked minimum to a new relative pose (the families of unidist/tracker.h): Newton on
// the NURBS pair's extremal system, alternating local projections for separated pairs, locally deepest points
// for overlapping ones. Internal.
#pragma once

#include "tracking/local_surface.h"
#include "tracking/nurbs_params.h"

#include <memory>

namespace unidist::tracking {

/// A minimum in the models' own frames (rigid: still valid as a start after any motion).
struct LocalMinimum {
  Eigen::Vector3d pA_A = Eigen::Vector3d::Zero();  ///< on A, A's frame
  Eigen::Vector3d pB_B = Eigen::Vector3d::Zero();  ///< on B, B's frame
  Hint hintA, hintB;
  double distance = 0;                                  ///< signed
  Eigen::Vector3d normal_A = Eigen::Vector3d::UnitZ();  ///< A → B (or the way B moves to separate), A's frame
};

class LocalUpdater {
 public:
  /// tol: convergence of distances; maxIterations: per update of one minimum.
  LocalUpdater(const Model& a, const Model& b, double tol, int maxIterations);
  ~LocalUpdater();

  /// Moves m to the local minimum near it at relative pose X_AB (B's frame → A's). False when it is lost (no
  /// convergence and no fallback answer), which drops it.
  bool update(LocalMinimum& m, const Eigen::Isometry3d& X_AB, Work& work) const;
  /// A minimum from a world contact of a global pass (points → own frames, hints from the models' exact queries).
  LocalMinimum fromWorld(const Eigen::Vector3d& pA_W, const Eigen::Vector3d& pB_W, double distance,
                         const Eigen::Vector3d& normal_W, const Eigen::Isometry3d& X_WA,
                         const Eigen::Isometry3d& X_WB) const;

 private:
  bool nurbsPair(LocalMinimum& m, const Eigen::Isometry3d& X_AB, Work& work) const;
  /// The local minimum of the pair apart (mesh pair descent, then the alternation); false at an overlap.
  bool apart(LocalMinimum& m, const Eigen::Isometry3d& X_AB, Work& work) const;
  /// Accelerated alternation; false when it met an overlap (m then holds the overlapping pair).
  bool alternateApart(LocalMinimum& m, const Eigen::Isometry3d& X_AB, Work& work) const;
  bool meshPairDescent(LocalMinimum& m, const Eigen::Isometry3d& X_AB, Work& work) const;
  void overlap(LocalMinimum& m, const Eigen::Isometry3d& X_AB, Work& work) const;
  void liftedOverlap(LocalMinimum& m, const Eigen::Isometry3d& X_AB, Work& work) const;
  LocalMinimum deepestOf(bool anchorA, const LocalMinimum& m, const Eigen::Isometry3d& X_AB, Work& work) const;

  const Model& a_;
  const Model& b_;
  std::unique_ptr<LocalSurface> la_, lb_;
  std::unique_ptr<ModelParams> nurbsA_, nurbsB_;  // both set only for a NURBS – NURBS pair
  double tol_;
  int maxIterations_;
  double reachA_, reachB_;  // support probe distance: the model's bounding radius
  double size_;             // the smaller bounding diagonal
};

}  // namespace unidist::tracking
