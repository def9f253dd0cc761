// Bullet shapes made of triangles (and the convex hull, triangulated) as unidist triangle meshes. Vertices are
// scaled as Bullet scales them (btVector3 products in btScalar), so the model holds the very triangles Bullet
// collides with. Welding, cleaning and the solid test are TriangleMesh's (mesh.h): a closed mesh becomes a
// solid, anything else an open surface. Bullet adds a concave shape's margin outside each of its triangles.
#include "shape_parts.h"

#include "unidist/mesh.h"

#include <BulletCollision/Gimpact/btGImpactShape.h>
#include <LinearMath/btConvexHullComputer.h>

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace unidist::bullet {
namespace {

struct MeshData {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<TriangleMesh::Triangle> triangles;

  ConvertedShape toShape(const btCollisionShape& shape, double outerMargin) {
    if (triangles.empty()) throw shapeError(shape, "has no triangles");
    return {std::make_shared<TriangleMesh>(std::move(vertices), std::move(triangles)), outerMargin,
            Eigen::Isometry3d::Identity()};
  }
};

btVector3 readVertex(const unsigned char* at, PHY_ScalarType type) {
  if (type == PHY_DOUBLE) {
    const auto* d = reinterpret_cast<const double*>(at);
    return {btScalar(d[0]), btScalar(d[1]), btScalar(d[2])};
  }
  const auto* f = reinterpret_cast<const float*>(at);
  return {btScalar(f[0]), btScalar(f[1]), btScalar(f[2])};
}

std::uint32_t readIndex(const unsigned char* at, PHY_ScalarType type, int k) {
  switch (type) {
    case PHY_INTEGER: return static_cast<std::uint32_t>(reinterpret_cast<const int*>(at)[k]);
    case PHY_SHORT: return reinterpret_cast<const unsigned short*>(at)[k];
    default: return at[k];  // PHY_UCHAR
  }
}

/// Appends one part of a striding mesh, every vertex multiplied by `scale` (and then `extraScale`) in btScalar.
void appendPart(const btCollisionShape& shape, const btStridingMeshInterface& mesh, int part, const btVector3& scale,
                const btVector3& extraScale, MeshData& out) {
  const unsigned char *vertexBase = nullptr, *indexBase = nullptr;
  int vertexCount = 0, vertexStride = 0, indexStride = 0, faceCount = 0;
  PHY_ScalarType vertexType = PHY_FLOAT, indexType = PHY_INTEGER;
  mesh.getLockedReadOnlyVertexIndexBase(&vertexBase, vertexCount, vertexType, vertexStride, &indexBase, indexStride,
                                        faceCount, indexType, part);
  struct Unlock {  // the part stays locked only while it is read, also when reading throws
    const btStridingMeshInterface& mesh;
    int part;
    ~Unlock() { mesh.unLockReadOnlyVertexBase(part); }
  } unlock{mesh, part};
  if (vertexType != PHY_FLOAT && vertexType != PHY_DOUBLE)
    throw shapeError(shape, "mesh part " + std::to_string(part) + " has vertices that are neither float nor double");
  if (indexType != PHY_INTEGER && indexType != PHY_SHORT && indexType != PHY_UCHAR)
    throw shapeError(shape, "mesh part " + std::to_string(part) + " has an index type other than int, short or uchar");
  const auto offset = static_cast<std::uint32_t>(out.vertices.size());
  for (int v = 0; v < vertexCount; ++v) {
    const btVector3 p = readVertex(vertexBase + static_cast<std::ptrdiff_t>(v) * vertexStride, vertexType);
    out.vertices.push_back(toEigen(p * scale * extraScale));
  }
  for (int f = 0; f < faceCount; ++f) {
    TriangleMesh::Triangle t{};
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t i = readIndex(indexBase + static_cast<std::ptrdiff_t>(f) * indexStride, indexType, k);
      if (i >= static_cast<std::uint32_t>(vertexCount))
        throw shapeError(shape, "mesh part " + std::to_string(part) + ", triangle " + std::to_string(f) +
                                    ": vertex index " + std::to_string(i) + " out of range (" +
                                    std::to_string(vertexCount) + " vertices)");
      t[static_cast<std::size_t>(k)] = offset + i;
    }
    out.triangles.push_back(t);
  }
}

MeshData readStridingMesh(const btCollisionShape& shape, const btStridingMeshInterface& mesh,
                          const btVector3& extraScale) {
  MeshData data;
  for (int part = 0; part < mesh.getNumSubParts(); ++part)
    appendPart(shape, mesh, part, mesh.getScaling(), extraScale, data);
  return data;
}

/// Collects triangles handed out by processAllTriangles (three vertices each; TriangleMesh welds them).
struct TriangleCollector : btTriangleCallback {
  MeshData data;
  void processTriangle(btVector3* triangle, int, int) override {
    const auto first = static_cast<std::uint32_t>(data.vertices.size());
    for (int k = 0; k < 3; ++k) data.vertices.push_back(toEigen(triangle[k]));
    data.triangles.push_back({first, first + 1, first + 2});
  }
};

ConvertedShape convertGImpactParts(const btCollisionShape& shape, const std::vector<const btGImpactMeshShapePart*>& parts) {
  // Each part carries its own scaling and margin (its primitive manager's); one outer margin must fit all.
  MeshData data;
  const double margin = parts.empty() ? 0.0 : double(parts.front()->getMargin());
  for (const btGImpactMeshShapePart* part : parts) {
    if (double(part->getMargin()) != margin)
      throw shapeError(shape, "mesh parts with different margins (" + std::to_string(margin) + ", " +
                                  std::to_string(double(part->getMargin())) + ") cannot share one outer margin");
    // Bullet offers the part's mesh only through a non-const accessor; it is only read here.
    const btStridingMeshInterface* mesh =
        const_cast<btGImpactMeshShapePart*>(part)->getTrimeshPrimitiveManager()->m_meshInterface;
    appendPart(shape, *mesh, part->getPart(), part->getLocalScaling(), btVector3(1, 1, 1), data);
  }
  return data.toShape(shape, margin);
}

}  // namespace

ConvertedShape convertConvexHull(const btConvexHullShape& s) {
  // Bullet collides with the hull of the scaled points, grown by the margin outside.
  std::vector<double> coords;
  coords.reserve(3 * static_cast<std::size_t>(s.getNumPoints()));
  for (int i = 0; i < s.getNumPoints(); ++i) {
    const btVector3 p = s.getScaledPoint(i);
    coords.insert(coords.end(), {double(p.x()), double(p.y()), double(p.z())});
  }
  btConvexHullComputer hull;
  if (s.getNumPoints() < 3 || hull.compute(coords.data(), 3 * sizeof(double), s.getNumPoints(), 0, 0) < 0 ||
      hull.faces.size() == 0)
    throw shapeError(s, "the points (" + std::to_string(s.getNumPoints()) + ") span no polygon or polytope");
  // The computer quantises coordinates internally: take each hull vertex from the input point it came from.
  MeshData data;
  for (int v = 0; v < hull.vertices.size(); ++v) {
    const auto i = 3 * static_cast<std::size_t>(hull.original_vertex_index[v]);
    data.vertices.emplace_back(coords[i], coords[i + 1], coords[i + 2]);
  }
  for (int f = 0; f < hull.faces.size(); ++f) {  // planar convex polygons: fans
    const btConvexHullComputer::Edge* start = &hull.edges[hull.faces[f]];
    const auto apex = static_cast<std::uint32_t>(start->getSourceVertex());
    for (const btConvexHullComputer::Edge* e = start->getNextEdgeOfFace(); e->getTargetVertex() != int(apex);
         e = e->getNextEdgeOfFace())
      data.triangles.push_back({apex, static_cast<std::uint32_t>(e->getSourceVertex()),
                                static_cast<std::uint32_t>(e->getTargetVertex())});
  }
  return data.toShape(s, double(s.getMargin()));
}

ConvertedShape convertTriangle(const btTriangleShape& s) {
  if (s.getLocalScaling() != btVector3(1, 1, 1))
    throw shapeError(s, "local scaling " + formatVector(s.getLocalScaling()) +
                            " is ignored by Bullet's triangle; scale the vertices instead");
  MeshData data;
  for (int k = 0; k < 3; ++k) data.vertices.push_back(toEigen(s.m_vertices1[k]));
  data.triangles.push_back({0, 1, 2});
  return data.toShape(s, double(s.getMargin()));
}

ConvertedShape convertBvhMesh(const btBvhTriangleMeshShape& s) {
  return readStridingMesh(s, *s.getMeshInterface(), btVector3(1, 1, 1)).toShape(s, double(s.getMargin()));
}

ConvertedShape convertScaledBvhMesh(const btScaledBvhTriangleMeshShape& s) {
  // The child's triangles (scaled by its mesh interface), scaled again by this shape's own scaling.
  const btBvhTriangleMeshShape& child = *s.getChildShape();
  return readStridingMesh(s, *child.getMeshInterface(), s.getLocalScaling()).toShape(s, double(s.getMargin()));
}

ConvertedShape convertGImpactMesh(const btCollisionShape& s) {
  const auto& gimpact = static_cast<const btGImpactShapeInterface&>(s);
  switch (gimpact.getGImpactShapeType()) {
    case CONST_GIMPACT_TRIMESH_SHAPE: {
      const auto& mesh = static_cast<const btGImpactMeshShape&>(s);
      std::vector<const btGImpactMeshShapePart*> parts;
      for (int i = 0; i < mesh.getMeshPartCount(); ++i) parts.push_back(mesh.getMeshPart(i));
      return convertGImpactParts(s, parts);
    }
    case CONST_GIMPACT_TRIMESH_SHAPE_PART:
      return convertGImpactParts(s, {&static_cast<const btGImpactMeshShapePart&>(s)});
    default:
      throw shapeError(s, "a GImpact compound: Bullet's GImpact algorithm recurses into its children itself; "
                          "convert each child shape instead");
  }
}

ConvertedShape convertHeightfield(const btHeightfieldTerrainShape& s) {
  // The grid is private: ask for every triangle over a box well beyond the shape's own bounds.
  btTransform identity;
  identity.setIdentity();
  btVector3 lo, hi;
  s.getAabb(identity, lo, hi);
  const btVector3 pad = (hi - lo) + btVector3(1, 1, 1);
  TriangleCollector collector;
  s.processAllTriangles(&collector, lo - pad, hi + pad);
  return collector.data.toShape(s, double(s.getMargin()));
}

}  // namespace unidist::bullet
