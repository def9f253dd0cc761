#include "unidist/bullet/shapes.h"

#include "eigen_bullet.h"
#include "unidist/mass.h"
#include "unidist/mesh.h"
#include "unidist/primitives.h"

#include <cmath>
#include <string>

namespace unidist::bullet {
namespace {

void rejectScaling(const btVector3& s, const char* name) {
  if (s.x() != 1 || s.y() != 1 || s.z() != 1)
    throw InputError(std::string(name) + ": local scaling is not supported (got " + std::to_string(s.x()) + ", " +
                     std::to_string(s.y()) + ", " + std::to_string(s.z()) + "); scale the model instead");
}

}  // namespace

ModelShapeData::ModelShapeData(std::shared_ptr<const Model> model, const ShapeOptions& options)
    : model_(std::move(model)), options_(options) {
  if (!model_) throw InputError("unidist Bullet shape: null model");
  if (!model_->localBounds().bounded())
    throw InputError("unidist Bullet shape: an unbounded model (" + model_->describe() +
                     ") cannot be a shape; use btStaticPlaneShape");
  if (std::isnan(options.tolerance) || std::isinf(options.tolerance))
    throw InputError("unidist Bullet shape: tolerance must be finite");
  if (const char* why = invalidDialSetting(options)) throw InputError(std::string("unidist Bullet shape: ") + why);
}

Eigen::Vector3d ModelShapeData::inertiaDiagonal(double mass) const {
  std::call_once(massOnce_, [this] {
    try {
      const MassProperties p = massProperties(*model_);
      unitInertia_ = p.inertia.diagonal() / p.volume;
    } catch (const InputError&) {
      unitInertia_.setZero();  // no finite volume: Bullet treats zero inertia as "no rotation"
    }
  });
  return mass * unitInertia_;
}

ModelConvexShape::ModelConvexShape(std::shared_ptr<const Model> model, const ShapeOptions& options)
    : data_(std::move(model), options) {
  m_shapeType = CUSTOM_CONVEX_SHAPE_TYPE;
  m_collisionMargin = 0;
}

btVector3 ModelConvexShape::localGetSupportingVertexWithoutMargin(const btVector3& dir) const {
  const Eigen::Vector3d d = toEigen(dir);
  return toBullet(data_.model()->support(d.squaredNorm() > 0 ? d : Eigen::Vector3d::UnitX()));
}

void ModelConvexShape::batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* dirs, btVector3* out,
                                                                         int n) const {
  for (int i = 0; i < n; ++i) out[i] = localGetSupportingVertexWithoutMargin(dirs[i]);
}

void ModelConvexShape::getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const {
  // Exact: the support point in each world axis direction, mapped back to the model frame. A box's in closed form
  // (|R|·h about the centre): Bullet asks for every body every step.
  const Eigen::Isometry3d X = toEigen(t);
  if (data_.model()->type() == ModelType::Box) {
    const Eigen::Vector3d h = static_cast<const Box&>(*data_.model()).halfExtents();
    const Eigen::Vector3d reach = X.linear().cwiseAbs() * h + Eigen::Vector3d::Constant(double(getMargin()));
    aabbMin = toBullet(X.translation() - reach);
    aabbMax = toBullet(X.translation() + reach);
    return;
  }
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d axis = X.linear().transpose().col(i);
    aabbMax[i] = btScalar((X * data_.model()->support(axis))[i] + getMargin());
    aabbMin[i] = btScalar((X * data_.model()->support(-axis))[i] - getMargin());
  }
}

void ModelConvexShape::calculateLocalInertia(btScalar mass, btVector3& inertia) const {
  inertia = toBullet(data_.inertiaDiagonal(double(mass)));
}

void ModelConvexShape::setLocalScaling(const btVector3& scaling) { rejectScaling(scaling, getName()); }

ModelConcaveShape::ModelConcaveShape(std::shared_ptr<const Model> model, const ShapeOptions& options)
    : data_(std::move(model), options) {
  m_shapeType = CUSTOM_CONCAVE_SHAPE_TYPE;
  m_collisionMargin = 0;
}

void ModelConcaveShape::processAllTriangles(btTriangleCallback* callback, const btVector3& aabbMin,
                                            const btVector3& aabbMax) const {
  const auto* mesh = dynamic_cast<const TriangleMesh*>(data_.model().get());
  if (!mesh) return;
  Aabb query;
  query.min = toEigen(aabbMin);
  query.max = toEigen(aabbMax);
  const auto& v = mesh->vertices();
  for (std::size_t t = 0; t < mesh->triangles().size(); ++t) {
    const auto& tri = mesh->triangles()[t];
    Aabb box;
    for (std::uint32_t i : tri) box.extend(v[i]);
    if ((box.max.array() < query.min.array()).any() || (box.min.array() > query.max.array()).any()) continue;
    btVector3 corners[3] = {toBullet(v[tri[0]]), toBullet(v[tri[1]]), toBullet(v[tri[2]])};
    callback->processTriangle(corners, 0, int(t));
  }
}

void ModelConcaveShape::getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const {
  const Aabb box = data_.model()->localBounds().transformed(toEigen(t));
  aabbMin = toBullet(box.min) - btVector3(getMargin(), getMargin(), getMargin());
  aabbMax = toBullet(box.max) + btVector3(getMargin(), getMargin(), getMargin());
}

void ModelConcaveShape::calculateLocalInertia(btScalar mass, btVector3& inertia) const {
  inertia = toBullet(data_.inertiaDiagonal(double(mass)));
}

void ModelConcaveShape::setLocalScaling(const btVector3& scaling) { rejectScaling(scaling, getName()); }

std::unique_ptr<btCollisionShape> makeShape(std::shared_ptr<const Model> model, const ShapeOptions& options) {
  if (!model) throw InputError("unidist Bullet shape: null model");
  if (model->isConvex() && model->localBounds().bounded())
    return std::make_unique<ModelConvexShape>(std::move(model), options);
  return std::make_unique<ModelConcaveShape>(std::move(model), options);
}

const ModelShapeData* shapeData(const btCollisionShape* shape) {
  if (!shape) return nullptr;
  if (shape->getShapeType() == CUSTOM_CONVEX_SHAPE_TYPE)
    if (const auto* s = dynamic_cast<const ModelConvexShape*>(shape)) return &s->data();
  if (shape->getShapeType() == CUSTOM_CONCAVE_SHAPE_TYPE)
    if (const auto* s = dynamic_cast<const ModelConcaveShape*>(shape)) return &s->data();
  return nullptr;
}

}  // namespace unidist::bullet
