// Point cloud: a finite set of points with optional normals. It has no inside (isSolid() is false), so its
// signed distance is the unsigned distance to the nearest point.
//
// Construction: at least one point, every coordinate finite; normals, when given, one per point and finite
// (InputError otherwise, naming the index). Non-zero normals are stored normalised; a zero normal is kept
// as "no normal" for that point.
//
// Point query (closestPoint): the nearest point, exact, through a bounding volume hierarchy over the points
// built lazily, once, thread-safely. feature = the point's index; param = (0, 0); normal = (q − p)/|q − p|,
// or when q coincides with p the stored normal (+z when there is none). Ties go to the first point the
// deterministic traversal meets.
// support(d): a scan over all points (exact).
// surfaceCells(): hierarchy nodes (face = node index >= 0) with a ball proved to hold the node's points;
// a leaf splits into one cell per point (face = −1 − point index, radius 0), and a one-point cell does not
// split further (splitCell appends nothing: a cell of radius 0 is already exact).
#pragma once

#include "unidist/model.h"

#include <atomic>
#include <memory>
#include <mutex>
#include <vector>

namespace unidist {

namespace cloud {
struct PointTree;
}
namespace lod {
class StandInCache;
}

class PointCloud final : public Model {
 public:
  explicit PointCloud(std::vector<Eigen::Vector3d> points, std::vector<Eigen::Vector3d> normals = {});
  ~PointCloud() override;
  PointCloud(const PointCloud&) = delete;
  PointCloud& operator=(const PointCloud&) = delete;

  ModelType type() const override { return ModelType::PointCloud; }
  SurfacePoint closestPoint(const Eigen::Vector3d& q_M) const override;
  Aabb localBounds() const override { return bounds_; }
  BoundingSphere localBoundingSphere() const override;
  bool isSolid() const override { return false; }
  Eigen::Vector3d support(const Eigen::Vector3d& dir_M) const override;
  std::vector<SurfaceCell> surfaceCells() const override;
  void splitCell(const SurfaceCell& cell, std::vector<SurfaceCell>& out) const override;
  std::string describe() const override;
  std::size_t memoryBytes() const override;
  /// "point-tree" (every query); "level-of-detail": the stand-ins asked for (atDetail).
  std::vector<StructureReport> structures() const override;
  void buildStructures() const override { tree(); }
  /// One point per cell of a voxel grid of side maxDeviation/√3 (the first in input order, with its normal);
  /// deviation: the farthest any dropped point lies from its cell's kept one. The cloud itself when nothing
  /// would be dropped.
  StandIn atDetail(double maxDeviation) const override;

  const std::vector<Eigen::Vector3d>& points() const { return points_; }
  /// Empty when the cloud has no normals; else one unit (or zero: none) normal per point.
  const std::vector<Eigen::Vector3d>& normals() const { return normals_; }

  /// The hierarchy over the points (built on first use, once, thread-safely). Internal type.
  const cloud::PointTree& tree() const;
  bool treeBuilt() const { return treeReady_.load(std::memory_order_acquire) != nullptr; }
  int treeBuildCount() const { return treeBuilds_.load(std::memory_order_acquire); }

 private:
  std::vector<Eigen::Vector3d> points_;
  std::vector<Eigen::Vector3d> normals_;
  Aabb bounds_;
  BoundingSphere sphere_;

  mutable std::once_flag treeOnce_;
  mutable std::unique_ptr<cloud::PointTree> tree_;
  mutable std::atomic<const cloud::PointTree*> treeReady_{nullptr};
  mutable std::atomic<int> treeBuilds_{0};
  std::unique_ptr<lod::StandInCache> standIns_;
};

}  // namespace unidist
