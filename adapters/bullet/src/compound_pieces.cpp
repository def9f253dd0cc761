#include "unidist/adapters/bullet_compounds.h"

#include "shape_parts.h"

#include <BulletCollision/CollisionShapes/btCompoundShape.h>

#include <algorithm>
#include <limits>

namespace unidist::bullet {
namespace {

void addChild(const btCollisionShape& child, const btTransform& X, CompoundPieces& out, double& margin) {
  std::vector<Eigen::Vector3d> points;
  if (child.getShapeType() == CONVEX_HULL_SHAPE_PROXYTYPE) {
    const auto& hull = static_cast<const btConvexHullShape&>(child);
    for (int i = 0; i < hull.getNumPoints(); ++i) points.push_back(toEigen(X * hull.getScaledPoint(i)));
    margin = std::min(margin, double(hull.getMargin()));
  } else if (child.getShapeType() == BOX_SHAPE_PROXYTYPE) {
    const btVector3 h = static_cast<const btBoxShape&>(child).getHalfExtentsWithMargin();
    for (int corner = 0; corner < 8; ++corner)
      points.push_back(toEigen(X * btVector3((corner & 1) ? h.x() : -h.x(), (corner & 2) ? h.y() : -h.y(),
                                             (corner & 4) ? h.z() : -h.z())));
    margin = 0;
  } else if (child.getShapeType() == COMPOUND_SHAPE_PROXYTYPE) {
    const auto& inner = static_cast<const btCompoundShape&>(child);
    for (int i = 0; i < inner.getNumChildShapes(); ++i)
      addChild(*inner.getChildShape(i), X * inner.getChildTransform(i), out, margin);
    return;
  } else {
    throw shapeError(child, "a compound given as convex pieces may hold btConvexHullShape, btBoxShape or "
                            "compounds of those");
  }
  out.pieces.push_back(std::move(points));
}

}  // namespace

CompoundPieces convexPiecesOfCompound(const btCompoundShape& compound) {
  CompoundPieces out;
  double margin = std::numeric_limits<double>::infinity();
  for (int i = 0; i < compound.getNumChildShapes(); ++i)
    addChild(*compound.getChildShape(i), compound.getChildTransform(i), out, margin);
  if (out.pieces.empty()) throw shapeError(compound, "the compound has no children");
  out.outerMargin = margin;
  return out;
}

}  // namespace unidist::bullet
