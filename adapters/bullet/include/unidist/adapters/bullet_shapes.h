// Bullet's own collision shapes as core models, so that the plugin can answer a pair of a unidist shape and a
// stock Bullet shape with the core algorithms. Conversion is exact (the same float coordinates Bullet uses,
// widened to double); it copies a mesh's vertices, so callers convert a shape once and cache the result.
//
// Supported: btSphereShape, btBoxShape, btCapsuleShape(X/Z), btCylinderShape(X/Z), btConeShape(X/Z),
// btMultiSphereShape of one ball or of two equal balls, btStaticPlaneShape, btConvexHullShape,
// btBvhTriangleMeshShape, btScaledBvhTriangleMeshShape, btGImpactMeshShape, btHeightfieldTerrainShape,
// btTriangleShape. Everything else throws InputError, compounds included: Bullet recurses into a compound's
// children itself, so each child arrives on its own.
//
// Local scaling is applied where the scaled shape is still the same kind of shape (meshes and hulls: per
// vertex; box and cylinder: per extent; capsule, cylinder and cone: axial and radial scale separately; sphere
// and multi-sphere: uniform only). Where Bullet's scaled shape is not what the scaling says (a non-uniformly
// scaled sphere is still a sphere to Bullet; a plane or a triangle ignores scaling), InputError says so.
#pragma once

#include "unidist/model.h"

#include <memory>

class btCollisionShape;

namespace unidist::bullet {

/// A Bullet shape as a core model. `outerMargin` is the thickness Bullet adds OUTSIDE the geometry the model
/// describes (btConvexHullShape's default 0.04, a cone's or a triangle's margin, a concave mesh's margin);
/// 0 where Bullet keeps the margin inside (box, sphere, capsule, cylinder, multi-sphere). Bullet's distance
/// to the shape is the model's distance minus outerMargin.
///
/// `X_SM` is the model's frame in the shape's local frame. unidist's capsule, cylinder and cone lie along z;
/// a Bullet shape along y (the default) or x gets the rotation that takes z to that axis, and a multi-sphere
/// the pose of its ball or capsule. Identity for every other shape. Pose the model at X_WS · X_SM.
struct ConvertedShape {
  std::shared_ptr<const Model> model;
  double outerMargin = 0;
  Eigen::Isometry3d X_SM = Eigen::Isometry3d::Identity();
};

/// Throws InputError naming the Bullet shape type for unsupported shapes, scalings or degenerate geometry.
ConvertedShape modelFromBulletShape(const btCollisionShape& shape);

}  // namespace unidist::bullet
