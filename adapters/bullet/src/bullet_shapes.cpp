// modelFromBulletShape(): dispatch on Bullet's shape type; the conversions live in convex_shapes.cpp and
// mesh_shapes.cpp.
#include "shape_parts.h"

#include <BulletCollision/Gimpact/btGImpactShape.h>

#include <sstream>

namespace unidist::bullet {

std::string formatVector(const btVector3& v) {
  std::ostringstream text;
  text << '(' << v.x() << ", " << v.y() << ", " << v.z() << ')';
  return text.str();
}

std::string shapeTypeName(const btCollisionShape& shape) {
  switch (shape.getShapeType()) {
    case SPHERE_SHAPE_PROXYTYPE: return "btSphereShape";
    case BOX_SHAPE_PROXYTYPE: return "btBoxShape";
    case CAPSULE_SHAPE_PROXYTYPE: return "btCapsuleShape";
    case CYLINDER_SHAPE_PROXYTYPE: return "btCylinderShape";
    case CONE_SHAPE_PROXYTYPE: return "btConeShape";
    case MULTI_SPHERE_SHAPE_PROXYTYPE: return "btMultiSphereShape";
    case STATIC_PLANE_PROXYTYPE: return "btStaticPlaneShape";
    case CONVEX_HULL_SHAPE_PROXYTYPE: return "btConvexHullShape";
    case TRIANGLE_SHAPE_PROXYTYPE: return "btTriangleShape";
    case TRIANGLE_MESH_SHAPE_PROXYTYPE: return "btBvhTriangleMeshShape";
    case SCALED_TRIANGLE_MESH_SHAPE_PROXYTYPE: return "btScaledBvhTriangleMeshShape";
    case GIMPACT_SHAPE_PROXYTYPE: return "btGImpactMeshShape";
    case TERRAIN_SHAPE_PROXYTYPE: return "btHeightfieldTerrainShape";
    case COMPOUND_SHAPE_PROXYTYPE: return "btCompoundShape";
    default: return std::string("shape type ") + std::to_string(shape.getShapeType()) + " (" + shape.getName() + ")";
  }
}

InputError shapeError(const btCollisionShape& shape, const std::string& what) {
  return InputError("Bullet " + shapeTypeName(shape) + ": " + what);
}

namespace {

ConvertedShape convert(const btCollisionShape& s) {
  switch (s.getShapeType()) {
    case SPHERE_SHAPE_PROXYTYPE: return convertSphere(static_cast<const btSphereShape&>(s));
    case BOX_SHAPE_PROXYTYPE: return convertBox(static_cast<const btBoxShape&>(s));
    case CAPSULE_SHAPE_PROXYTYPE: return convertCapsule(static_cast<const btCapsuleShape&>(s));
    case CYLINDER_SHAPE_PROXYTYPE: return convertCylinder(static_cast<const btCylinderShape&>(s));
    case CONE_SHAPE_PROXYTYPE: return convertCone(static_cast<const btConeShape&>(s));
    case MULTI_SPHERE_SHAPE_PROXYTYPE: return convertMultiSphere(static_cast<const btMultiSphereShape&>(s));
    case STATIC_PLANE_PROXYTYPE: return convertPlane(static_cast<const btStaticPlaneShape&>(s));
    case CONVEX_HULL_SHAPE_PROXYTYPE: return convertConvexHull(static_cast<const btConvexHullShape&>(s));
    case TRIANGLE_SHAPE_PROXYTYPE: return convertTriangle(static_cast<const btTriangleShape&>(s));
    case TRIANGLE_MESH_SHAPE_PROXYTYPE: return convertBvhMesh(static_cast<const btBvhTriangleMeshShape&>(s));
    case SCALED_TRIANGLE_MESH_SHAPE_PROXYTYPE:
      return convertScaledBvhMesh(static_cast<const btScaledBvhTriangleMeshShape&>(s));
    case GIMPACT_SHAPE_PROXYTYPE: return convertGImpactMesh(s);
    case TERRAIN_SHAPE_PROXYTYPE: return convertHeightfield(static_cast<const btHeightfieldTerrainShape&>(s));
    case COMPOUND_SHAPE_PROXYTYPE:
      throw shapeError(s, "compound shapes are not converted: Bullet recurses into the children itself and "
                          "pairs each child with the other shape, so convert the children");
    default: throw shapeError(s, "not supported (no unidist model for this Bullet shape type)");
  }
}

}  // namespace

ConvertedShape modelFromBulletShape(const btCollisionShape& shape) {
  try {
    return convert(shape);
  } catch (const InputError& e) {
    // The core's own messages (a degenerate mesh, a bad size) do not know the shape: say which one it was.
    const std::string message = e.what();
    if (message.rfind("Bullet ", 0) == 0) throw;
    throw shapeError(shape, message);
  }
}

}  // namespace unidist::bullet
