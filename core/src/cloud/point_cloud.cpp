// PointCloud: validation, the nearest-point query through the lazily built tree, and tree-node surface cells.
// See unidist/point_cloud.h.
#include "unidist/point_cloud.h"

#include "cloud/point_support.h"
#include "lod/decimate.h"
#include "cloud/point_tree.h"
#include "primitives/common.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace unidist {

PointCloud::~PointCloud() = default;

PointCloud::PointCloud(std::vector<Eigen::Vector3d> points, std::vector<Eigen::Vector3d> normals)
    : points_(std::move(points)), normals_(std::move(normals)), standIns_(std::make_unique<lod::StandInCache>()) {
  if (points_.empty()) throw InputError("point cloud: no points");
  if (points_.size() >= std::numeric_limits<std::uint32_t>::max())
    throw InputError("point cloud: too many points (" + std::to_string(points_.size()) + ")");
  if (!normals_.empty() && normals_.size() != points_.size())
    throw InputError("point cloud: " + std::to_string(normals_.size()) + " normals for " +
                     std::to_string(points_.size()) + " points");
  const auto text = [](const Eigen::Vector3d& v) {
    return prim::formatNumber(v.x()) + ", " + prim::formatNumber(v.y()) + ", " + prim::formatNumber(v.z());
  };
  for (std::size_t i = 0; i < points_.size(); ++i)
    prim::requireModelCoordinate(points_[i], "point cloud: point", i);
  for (std::size_t i = 0; i < normals_.size(); ++i) {
    if (!normals_[i].allFinite())
      throw InputError("point cloud: normal " + std::to_string(i) + " has a non-finite coordinate (" +
                       text(normals_[i]) + ")");
    normals_[i] = prim::unitOr(normals_[i], Eigen::Vector3d::Zero());
  }
  for (const Eigen::Vector3d& p : points_) bounds_.extend(p);
  sphere_.center = bounds_.center();
  double farthest = 0;
  for (const Eigen::Vector3d& p : points_) farthest = std::max(farthest, (p - sphere_.center).squaredNorm());
  sphere_.radius = mesh::paddedRadius(std::sqrt(farthest));
}

const cloud::PointTree& PointCloud::tree() const {
  std::call_once(treeOnce_, [this] {
    tree_ = std::make_unique<cloud::PointTree>(cloud::buildPointTree(points_));
    treeBuilds_.fetch_add(1, std::memory_order_acq_rel);
    treeReady_.store(tree_.get(), std::memory_order_release);
  });
  return *tree_;
}

SurfacePoint PointCloud::closestPoint(const Eigen::Vector3d& q) const {
  double squared = 0;
  const std::uint32_t i = cloud::nearestPoint(tree(), points_, q, squared);
  SurfacePoint s;
  s.point = points_[i];
  s.feature = static_cast<int>(i);
  const Eigen::Vector3d gap = q - s.point;
  s.signedDistance = prim::robustNorm(gap);
  Eigen::Vector3d fallback = Eigen::Vector3d::UnitZ();
  if (!normals_.empty() && normals_[i] != Eigen::Vector3d::Zero()) fallback = normals_[i];
  s.normal = prim::unitOr(gap, fallback);
  return s;
}

BoundingSphere PointCloud::localBoundingSphere() const { return sphere_; }

Eigen::Vector3d PointCloud::support(const Eigen::Vector3d& dir) const { return supportOfPoints(points_, dir); }

namespace {

SurfaceCell nodeCell(const cloud::PointTree& t, const std::vector<Eigen::Vector3d>& points, std::uint32_t node) {
  SurfaceCell c;
  c.center = t.spheres[node].center;
  c.radius = t.spheres[node].radius;
  c.sample = points[t.tree.order[t.ranges[node][0]]];
  c.face = static_cast<int>(node);
  if (c.radius == 0) c.center = c.sample;  // all the node's points coincide: an exact one-point cell
  return c;
}

SurfaceCell pointCell(const std::vector<Eigen::Vector3d>& points, std::uint32_t i) {
  SurfaceCell c;
  c.center = c.sample = points[i];
  c.radius = 0;
  c.face = -1 - static_cast<int>(i);
  return c;
}

}  // namespace

std::vector<SurfaceCell> PointCloud::surfaceCells() const {
  const cloud::PointTree& t = tree();
  const mesh::BvhNode& root = t.tree.nodes[0];
  if (root.leaf()) return {nodeCell(t, points_, 0)};
  return {nodeCell(t, points_, root.first), nodeCell(t, points_, root.first + 1)};
}

void PointCloud::splitCell(const SurfaceCell& cell, std::vector<SurfaceCell>& out) const {
  if (cell.face < 0 || cell.radius == 0) return;  // one point (or coinciding points): nothing smaller
  const cloud::PointTree& t = tree();
  const mesh::BvhNode& n = t.tree.nodes[static_cast<std::size_t>(cell.face)];
  if (n.leaf()) {
    for (std::uint32_t s = n.first; s < n.first + n.count; ++s) out.push_back(pointCell(points_, t.tree.order[s]));
  } else {
    out.push_back(nodeCell(t, points_, n.first));
    out.push_back(nodeCell(t, points_, n.first + 1));
  }
}

std::string PointCloud::describe() const {
  return "point cloud: " + std::to_string(points_.size()) + " points" + (normals_.empty() ? "" : ", with normals");
}

std::vector<StructureReport> PointCloud::structures() const {
  const cloud::PointTree* t = treeReady_.load(std::memory_order_acquire);
  return {{"point-tree", t != nullptr, t ? sizeof(*t) + t->memoryBytes() : 0}, standIns_->report()};
}

StandIn PointCloud::atDetail(double maxDeviation) const {
  lod::checkLevel(maxDeviation);
  if (maxDeviation == 0) return StandIn{this, 0.0};
  return standIns_->get(*this, maxDeviation, [this](double level) { return lod::decimate(*this, level); });
}

std::size_t PointCloud::memoryBytes() const {
  std::size_t bytes = sizeof(*this) + points_.capacity() * sizeof(Eigen::Vector3d) +
                      normals_.capacity() * sizeof(Eigen::Vector3d);
  if (const cloud::PointTree* t = treeReady_.load(std::memory_order_acquire)) bytes += sizeof(*t) + t->memoryBytes();
  return bytes + standIns_->report().bytes;
}

}  // namespace unidist
