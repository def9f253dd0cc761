// The conversions behind modelFromBulletShape(), one family per file: the convex primitives
// (convex_shapes.cpp) and the shapes made of triangles (mesh_shapes.cpp).
#pragma once

#include "unidist/adapters/bullet_shapes.h"
#include "unidist/types.h"

#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>
#include <BulletCollision/CollisionShapes/btTriangleShape.h>
#include <btBulletCollisionCommon.h>

#include <string>

namespace unidist::bullet {

inline Eigen::Vector3d toEigen(const btVector3& v) { return {double(v.x()), double(v.y()), double(v.z())}; }

/// "(x, y, z)" for messages.
std::string formatVector(const btVector3& v);

/// The InputError for a shape: "Bullet <type name>: <what>".
InputError shapeError(const btCollisionShape& shape, const std::string& what);

/// The Bullet class name of a shape type, e.g. "btCapsuleShape".
std::string shapeTypeName(const btCollisionShape& shape);

ConvertedShape convertSphere(const btSphereShape& s);
ConvertedShape convertBox(const btBoxShape& s);
ConvertedShape convertCapsule(const btCapsuleShape& s);
ConvertedShape convertCylinder(const btCylinderShape& s);
ConvertedShape convertCone(const btConeShape& s);
ConvertedShape convertMultiSphere(const btMultiSphereShape& s);
ConvertedShape convertPlane(const btStaticPlaneShape& s);

ConvertedShape convertConvexHull(const btConvexHullShape& s);
ConvertedShape convertTriangle(const btTriangleShape& s);
ConvertedShape convertBvhMesh(const btBvhTriangleMeshShape& s);
ConvertedShape convertScaledBvhMesh(const btScaledBvhTriangleMeshShape& s);
ConvertedShape convertGImpactMesh(const btCollisionShape& s);  // a btGImpactShapeInterface; checks the kind
ConvertedShape convertHeightfield(const btHeightfieldTerrainShape& s);

}  // namespace unidist::bullet
