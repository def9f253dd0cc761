// unidist models as Bullet collision shapes. A shape holds a shared, immutable core model; its pose is the
// collision object's (or compound child's) world transform, read each step. Convex models (primitives other
// than the torus and the half-space, convex meshes) become a CUSTOM_CONVEX_SHAPE_TYPE shape with the model's
// exact support map, so Bullet's own ray tests, convex sweeps and CCD work on them; everything else (meshes,
// point clouds, NURBS, the torus) a CUSTOM_CONCAVE_SHAPE_TYPE shape. Both have margin 0 (the plugin's
// algorithm is exact). Local scaling other than (1,1,1) is rejected (InputError): scale the model instead.
// Collisions between these shapes and anything else go through the algorithm that
// unidist::bullet::registerAlgorithms() installs (plugin.h); without it Bullet would crash on the concave type.
#pragma once

#include "unidist/model.h"
#include "unidist/query_options.h"

#include <btBulletCollisionCommon.h>

#include <memory>
#include <mutex>

namespace unidist::bullet {

/// The dial of this shape's contact queries (unidist/query_options.h); a pair uses the stricter of its two
/// shapes' dials. tolerance < 0: 1e-4 × the smaller bounding diagonal of the pair. detailA: this shape's level
/// of detail (its model's stand-in, Model::atDetail, answers its contacts); detailB is ignored.
struct ShapeOptions : QueryOptions {};

/// What both shape classes carry.
class ModelShapeData {
 public:
  ModelShapeData(std::shared_ptr<const Model> model, const ShapeOptions& options);
  const std::shared_ptr<const Model>& model() const { return model_; }
  const QueryOptions& queryOptions() const { return options_; }
  /// Diagonal of the unit-density inertia about the centre of mass, in model axes, scaled to `mass` (zero for a
  /// model without a finite volume). Computed once, on first use.
  Eigen::Vector3d inertiaDiagonal(double mass) const;

 private:
  std::shared_ptr<const Model> model_;
  ShapeOptions options_;
  mutable std::once_flag massOnce_;
  mutable Eigen::Vector3d unitInertia_ = Eigen::Vector3d::Zero();  // per unit mass
};

class ModelConvexShape final : public btConvexInternalShape {
 public:
  BT_DECLARE_ALIGNED_ALLOCATOR();
  ModelConvexShape(std::shared_ptr<const Model> model, const ShapeOptions& options = {});
  const ModelShapeData& data() const { return data_; }

  btVector3 localGetSupportingVertexWithoutMargin(const btVector3& dir) const override;
  void batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* dirs, btVector3* out,
                                                         int n) const override;
  void getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const override;
  void calculateLocalInertia(btScalar mass, btVector3& inertia) const override;
  void setLocalScaling(const btVector3& scaling) override;
  const char* getName() const override { return "UnidistConvex"; }

 private:
  ModelShapeData data_;
};

class ModelConcaveShape final : public btConcaveShape {
 public:
  BT_DECLARE_ALIGNED_ALLOCATOR();
  ModelConcaveShape(std::shared_ptr<const Model> model, const ShapeOptions& options = {});
  const ModelShapeData& data() const { return data_; }

  /// Meshes feed their triangles (for Bullet's ray tests and sweeps); other models feed none.
  void processAllTriangles(btTriangleCallback* callback, const btVector3& aabbMin,
                           const btVector3& aabbMax) const override;
  void getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const override;
  void calculateLocalInertia(btScalar mass, btVector3& inertia) const override;
  void setLocalScaling(const btVector3& scaling) override;
  const btVector3& getLocalScaling() const override { return unitScaling_; }
  const char* getName() const override { return "UnidistConcave"; }

 private:
  ModelShapeData data_;
  btVector3 unitScaling_{1, 1, 1};
};

/// The right shape class for the model. Throws InputError for a null or unbounded model (a half-space: use
/// btStaticPlaneShape, which the plugin's algorithm handles).
std::unique_ptr<btCollisionShape> makeShape(std::shared_ptr<const Model> model, const ShapeOptions& options = {});

/// The unidist data of a shape, or null when it is not a unidist shape.
const ModelShapeData* shapeData(const btCollisionShape* shape);

}  // namespace unidist::bullet
