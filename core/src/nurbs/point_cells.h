// A lazily filled grid of query cells for the NURBS point query: per cell (a ball of query points) the few
// subdivision nodes that can hold the nearest point of any query in it, each proved convex for every such
// query (point_convexity.h), and the patch corners that can. Everything else is excluded once for the whole
// cell — by distance (farther than the cell's nearest surface point can be), by the normal cones, or by the
// gradient's sign — so a query in a settled cell is a short Newton run in one node and a tangent-plane bound
// in the others, where the full search would rebuild the same proofs per query. A cell that cannot be settled
// (it reaches a centre of curvature or a pole, or too many nodes survive) is marked and its queries take the
// full search. A cell is made by the first query that lands in it, from its centre alone, so that an answer
// depends on the query point only, never on which queries came before (one atomic pointer per cell:
// concurrent queries never block; two threads may build the same cell, identically, and one copy is
// dropped). Internal.
#pragma once

#include "nurbs/patch_search.h"

#include <atomic>
#include <memory>
#include <mutex>
#include <vector>

namespace unidist::nurbs {

class PointCells {
 public:
  /// Cells of about `cell` across over the box [lo, hi] (queries outside take the full search).
  PointCells(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double cell);
  ~PointCells();
  PointCells(const PointCells&) = delete;
  PointCells& operator=(const PointCells&) = delete;

  /// The nearest point of the patches to q, proved to `tolerance` (result.lowerBound), or false when q's cell
  /// is not settled (the caller runs the full search).
  bool closest(const PatchForest& forest, const std::vector<RationalBezierPatch>& patches, const Eigen::Vector3d& q,
               double modelSize, double tolerance, SearchResult& result) const;

  std::size_t bytes() const { return bytes_.load(); }
  bool built() const { return made_.load() > 0; }

 private:
  struct Candidate {
    const PatchNode* node;
    double curvature;  // leastCurvature over the cell's ball
  };
  struct Cell {
    bool settled = false;
    // A run starts at the centre's nearest point (patch, s, t) moved by follow·(q − centre), kept to its node.
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    int patch = -1;
    Eigen::Vector2d foot = Eigen::Vector2d::Zero();
    Eigen::Matrix<double, 2, 3> follow = Eigen::Matrix<double, 2, 3>::Zero();
    std::vector<Candidate> candidates;
    std::vector<PatchHit> corners;  // patch corners that may be nearest (value unset)
  };
  const Cell* cellAt(const PatchForest& forest, const std::vector<RationalBezierPatch>& patches, int index,
                     double modelSize, double tolerance) const;
  static Eigen::Vector2d runStart(const Cell& cell, const PatchNode& n, const PatchHit* best, const Eigen::Vector3d& q);
  std::unique_ptr<Cell> build(const PatchForest& forest, const std::vector<RationalBezierPatch>& patches,
                              const Eigen::Vector3d& centre, double reach, double modelSize, double tolerance) const;

  Eigen::Vector3d lo_;
  double size_;
  Eigen::Vector3i count_;
  mutable std::once_flag cellsOnce_;  // the slots are allocated by the first query
  mutable std::unique_ptr<std::atomic<const Cell*>[]> cells_;
  mutable std::atomic<std::size_t> bytes_{0}, made_{0};
};

}  // namespace unidist::nurbs
