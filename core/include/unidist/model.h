// The one abstract model every representation implements (the "geometry object" of Johnson & Cohen,
// Unified Distance Queries in a Heterogeneous Model Environment, 2004). Everything is in the model's own
// frame; a pose is given per query and never stored. Models are immutable after construction, and every
// member function is const and safe to call from several threads at once.
#pragma once

#include "unidist/types.h"

#include <cstddef>
#include <string>
#include <vector>

namespace unidist {

enum class ModelType { Sphere, Box, Capsule, Cylinder, Cone, Torus, Plane, Mesh, PointCloud, Nurbs };

const char* toString(ModelType t);

/// A piece of a model's surface for branch-and-bound searches. Every surface point of the piece lies
/// within `radius` of `center` (proved, not estimated); `sample` is a point on the surface inside the piece.
/// `face` and the parameter box [u0,u1]x[v0,v1] are the model's own business (used to split the cell).
struct SurfaceCell {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 0;
  Eigen::Vector3d sample = Eigen::Vector3d::Zero();
  int face = 0;
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
};

/// One acceleration structure a model builds on first need, once (for `unidist info`, tests and benchmarks).
/// A model at a level of detail (Model::atDetail): the model answered in its place and how far its surface is
/// proved to lie from the original's. `model` is never null and lives as long as the original model.
class Model;

struct StandIn {
  const Model* model = nullptr;
  double deviation = 0;  ///< proved Hausdorff distance between the two surfaces (0: the model itself)
};

struct StructureReport {
  std::string name;       ///< e.g. "bvh", "winding", "point-tree", "patch-tree", "contact-mesh"
  bool built = false;
  std::size_t bytes = 0;  ///< what it holds now (0 until built; a patch tree grows as queries refine it)
};

class Model {
 public:
  virtual ~Model() = default;

  virtual ModelType type() const = 0;

  /// Closest point of the model's surface to q_M (model frame). For a solid, signedDistance < 0 when q_M is
  /// inside. Defined for every finite q_M: where the closest point is not unique the model documents its choice.
  virtual SurfacePoint closestPoint(const Eigen::Vector3d& q_M) const = 0;

  /// Bounds in the model frame.
  virtual Aabb localBounds() const = 0;
  virtual BoundingSphere localBoundingSphere() const;

  /// A solid has an inside (signed distances); a point cloud or an open surface does not.
  virtual bool isSolid() const = 0;
  /// True only when the model is a convex solid (then support() is its exact support map).
  virtual bool isConvex() const { return false; }
  /// Fast point-in-solid test; false for models without an inside.
  virtual bool inside(const Eigen::Vector3d& q_M) const { return isSolid() && closestPoint(q_M).signedDistance < 0; }

  /// A point of the model maximising dir·p (the support map of its convex hull). dir need not be unit.
  virtual Eigen::Vector3d support(const Eigen::Vector3d& dir_M) const = 0;

  /// Pieces covering the whole surface, for branch-and-bound; empty for unbounded models.
  virtual std::vector<SurfaceCell> surfaceCells() const = 0;
  /// Splits a cell into smaller ones that together cover it (appended to out).
  virtual void splitCell(const SurfaceCell& cell, std::vector<SurfaceCell>& out) const = 0;

  /// One line saying what the model is (type and sizes), for `unidist info`.
  virtual std::string describe() const = 0;
  /// Bytes held by the model, including any acceleration structure built so far.
  virtual std::size_t memoryBytes() const = 0;
  /// The structures this model builds lazily and whether each exists yet; empty for models that need none.
  virtual std::vector<StructureReport> structures() const { return {}; }
  /// Builds every lazily built structure now: before a real-time loop, or to see what they cost.
  virtual void buildStructures() const {}

  /// The model at a level of detail: a cheaper stand-in whose surface is proved to lie within `maxDeviation`
  /// (Hausdorff distance, model length) of this one's — a NURBS model's tessellation, a point cloud's
  /// decimation (docs/dial.md, "Level of detail") — built on the first request for that level, once, and kept
  /// with the model (thread-safe). The model itself (deviation 0) for 0, for models with no coarser form, and
  /// where no stand-in within the level can be built. InputError for a negative or non-finite maxDeviation.
  virtual StandIn atDetail(double maxDeviation) const;
};

}  // namespace unidist
