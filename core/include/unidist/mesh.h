// Triangle mesh: a closed, consistently oriented surface (a solid) or an open surface, with an exact point
// query accelerated by a bounding volume hierarchy built lazily, once, on the first query that needs it.
//
// Construction (docs/query-contract.md, "A mesh is a solid when ..."):
//  1. validate: every coordinate finite, every index in range, at least one triangle (InputError otherwise,
//     naming the vertex or triangle);
//  2. weld vertices at exactly equal positions (-0 and +0 are equal);
//  3. drop zero-area triangles (two welded indices equal, or three collinear vertices, decided exactly) and
//     duplicated triangles (the same three welded vertices in either orientation; the first one is kept);
//     throw InputError when nothing is left;
//  4. drop vertices no kept triangle uses;
//  5. solid = every edge is shared by exactly two triangles that traverse it in opposite directions; a
//     solid with negative signed volume (normals pointing inward) has all its triangles flipped (vertices 1
//     and 2 swapped) so that normals point outward;
//  6. convex = solid, connected, every edge convex (the neighbour's far vertex on or below the triangle's
//     plane within 1e-12 × the bounding-box diagonal; coplanar neighbours facing the same way) and every
//     vertex's angle sum at most 2π (+1e-9). A closed immersed surface that is locally convex everywhere
//     bounds a convex body (van Heijenoort 1952), so these O(n) local tests decide convexity for any mesh
//     that does not pass through itself. Meshes with at most 2e7 triangle–vertex pairs are also checked
//     by the definition (every vertex on the inner side of every face plane, same tolerance).
//
// Point query (closestPoint): exact closest point over all triangles (depth-first descent of the hierarchy,
// nearer child first, pruned by the squared distance to the nodes' boxes; exact point–triangle at the leaves,
// mesh/point_triangle.h).
//  * feature = index of the triangle (in triangles(), i.e. after cleaning; sourceTriangle() maps it back to
//    the input); param = the point's barycentric coordinates (b1, b2) in that triangle:
//    point = (1 − b1 − b2)·v0 + b1·v1 + b2·v2. closestFeature() also gives the Voronoi feature (face, edge,
//    vertex) of the triangle that holds the point.
//  * solid: signedDistance < 0 inside. The side is decided by the angle-weighted pseudo-normal of the
//    closest feature (Bærentzen & Aanæs 2005), and by the generalized winding number where that test is
//    ambiguous (|cos| < 1e-4 between q − p and the pseudo-normal, or a non-manifold vertex).
//    normal = (q − p)/|q − p| outside, (p − q)/|p − q| inside, the feature's pseudo-normal when q is on the
//    surface.
//  * open: signedDistance = the unsigned distance (>= 0); normal = (q − p)/|q − p|, or the triangle's normal
//    when q is on the surface.
//  * ties (several closest points at exactly the same distance) go to the first triangle the deterministic
//    traversal meets, so answers are reproducible across runs and threads.
// inside(q): generalized winding number > 1/2 (solids only; false for an open mesh). Far parts of the
// mesh are summed exactly through their boundary (see core/src/mesh/winding.h), not approximated.
// support(d): for a convex mesh hill climbing over vertex neighbours (exact on a convex polytope); otherwise
// a scan over all vertices (the convex hull's support point, O(vertices)).
// surfaceCells(): cells are hierarchy nodes (face = node index >= 0; centre and radius: a ball proved to
// hold every triangle of the node; sample: a vertex of one of them). A leaf node splits into one cell per
// triangle, and a triangle cell (face = −1 − triangle index) into its four midpoint sub-triangles; the
// sub-triangle is encoded in barycentric coordinates as the corner (u0, v0) and the two vertices (u1, v0)
// and (u0, v1) (u1 < u0 and v1 < v0 for the inverted middle child), so cells shrink to points.
#pragma once

#include "unidist/model.h"

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

namespace unidist {

namespace mesh {
struct MeshBvh;
struct WindingData;
struct TriangleClosest;
}  // namespace mesh

/// Voronoi feature of a triangle (v0, v1, v2) that holds a closest point.
enum class TriangleFeature : std::uint8_t { Face, Edge01, Edge12, Edge20, Vertex0, Vertex1, Vertex2 };

/// What closestFeature() returns: the point query plus which triangle feature holds the point.
struct MeshPoint {
  SurfacePoint surface;  ///< as closestPoint()
  int triangle = 0;      ///< = surface.feature
  TriangleFeature feature = TriangleFeature::Face;
};

class TriangleMesh final : public Model {
 public:
  using Triangle = std::array<std::uint32_t, 3>;

  /// What construction found and did (for `unidist info` and tests).
  struct Stats {
    std::size_t inputVertices = 0, inputTriangles = 0;
    std::size_t weldedVertices = 0;        ///< distinct positions among the input vertices
    std::size_t unusedVertices = 0;        ///< distinct positions no kept triangle uses (dropped)
    std::size_t droppedZeroArea = 0;       ///< triangles with zero area after welding
    std::size_t droppedDuplicate = 0;      ///< repeated triangles (same welded vertices, either orientation)
    std::size_t boundaryEdges = 0;         ///< edges used by one triangle
    std::size_t nonManifoldEdges = 0;      ///< edges used by three or more triangles
    std::size_t misorientedEdges = 0;      ///< edges used by two triangles in the same direction
    std::size_t nonManifoldVertices = 0;   ///< solid only: vertices whose triangles form more than one fan
    bool closed = false;                   ///< every edge used by exactly two triangles
    bool consistentlyOriented = false;     ///< no edge used twice in the same direction
    bool solid = false;                    ///< closed and consistently oriented
    bool flipped = false;                  ///< a solid given inward-oriented, turned outward
    bool convex = false;
    double signedVolume = 0;               ///< after any flip (> 0 for a solid unless it is flat)
  };

  /// Validates and cleans the input (see the top of this file). Throws InputError naming the problem.
  TriangleMesh(std::vector<Eigen::Vector3d> vertices, std::vector<Triangle> triangles);
  ~TriangleMesh() override;
  TriangleMesh(const TriangleMesh&) = delete;
  TriangleMesh& operator=(const TriangleMesh&) = delete;

  ModelType type() const override { return ModelType::Mesh; }
  SurfacePoint closestPoint(const Eigen::Vector3d& q_M) const override;
  /// closestPoint() plus the Voronoi feature of the triangle holding the point.
  MeshPoint closestFeature(const Eigen::Vector3d& q_M) const;
  /// The surface point of q_M's closest point c on triangle t (mesh::closestOnTriangle's answer), signed and
  /// given a normal as closestPoint() does: for searches that find the triangle themselves (the tracker's walk).
  SurfacePoint surfacePointOn(const Eigen::Vector3d& q_M, int t, const mesh::TriangleClosest& c) const;
  Aabb localBounds() const override { return bounds_; }
  BoundingSphere localBoundingSphere() const override;
  bool isSolid() const override { return stats_.solid; }
  bool isConvex() const override { return stats_.convex; }
  bool inside(const Eigen::Vector3d& q_M) const override;
  /// Generalized winding number at q (1 inside and 0 outside a solid; fractional for an open mesh).
  double windingNumber(const Eigen::Vector3d& q_M) const;
  Eigen::Vector3d support(const Eigen::Vector3d& dir_M) const override;
  std::vector<SurfaceCell> surfaceCells() const override;
  void splitCell(const SurfaceCell& cell, std::vector<SurfaceCell>& out) const override;
  std::string describe() const override;
  std::size_t memoryBytes() const override;
  /// "bvh" (every query) and "winding" (inside tests of points far from the surface: containment).
  std::vector<StructureReport> structures() const override;
  void buildStructures() const override;

  const Stats& stats() const { return stats_; }
  /// The cleaned model: welded, unused vertices dropped, triangles dropped and (for a flipped solid) reoriented.
  const std::vector<Eigen::Vector3d>& vertices() const { return vertices_; }
  const std::vector<Triangle>& triangles() const { return triangles_; }
  /// Index in the constructor's triangle list of cleaned triangle t.
  std::uint32_t sourceTriangle(int t) const { return source_[static_cast<std::size_t>(t)]; }
  /// Outward unit normal of triangle t (orientation v0 → v1 → v2, right-handed).
  const Eigen::Vector3d& faceNormal(int t) const { return faceNormals_[static_cast<std::size_t>(t)]; }

  /// The bounding volume hierarchy (built on the first call, once, thread-safely). Internal type; exposed
  /// for the pair searches in core/src.
  const mesh::MeshBvh& bvh() const;
  /// Whether the hierarchy exists yet, how many times it was built (0 or 1) and how long that took.
  bool bvhBuilt() const { return bvhReady_.load(std::memory_order_acquire) != nullptr; }
  int bvhBuildCount() const { return bvhBuilds_.load(std::memory_order_acquire); }
  double bvhBuildMicroseconds() const { return bvhMicros_.load(std::memory_order_acquire); }

 private:
  std::vector<double> computeNormals();  // returns each vertex's sum of corner angles (solids only)
  void decideConvexity(const std::vector<double>& angleSums);
  Eigen::Vector3d pseudoNormal(int triangle, TriangleFeature f) const;
  bool insideByWinding(const Eigen::Vector3d& q) const;
  const mesh::WindingData& winding() const;

  std::vector<Eigen::Vector3d> vertices_;
  std::vector<Triangle> triangles_;
  std::vector<std::uint32_t> source_;
  std::vector<Eigen::Vector3d> faceNormals_;
  /// Half-edge 3t + k runs from triangles_[t][k] to triangles_[t][(k+1)%3]; twin_ is the opposite half-edge
  /// when the edge has exactly two triangles traversing it in opposite directions, else kNoTwin.
  std::vector<std::uint32_t> twin_;
  std::vector<Eigen::Vector3d> vertexPseudoNormals_;  // solid only (angle-weighted, unit)
  std::vector<std::uint8_t> nonManifoldVertex_;       // solid only
  std::vector<std::uint32_t> adjacencyStart_, adjacency_;  // convex only: vertex neighbours (CSR)
  std::array<std::uint32_t, 14> extremeVertices_{};        // convex only: starts for hill climbing
  Aabb bounds_;
  BoundingSphere sphere_;
  Stats stats_;

  mutable std::once_flag bvhOnce_;
  mutable std::unique_ptr<mesh::MeshBvh> bvh_;
  mutable std::atomic<const mesh::MeshBvh*> bvhReady_{nullptr};
  mutable std::atomic<int> bvhBuilds_{0};
  mutable std::atomic<double> bvhMicros_{0};
  mutable std::once_flag windingOnce_;
  mutable std::unique_ptr<mesh::WindingData> winding_;
  mutable std::atomic<const mesh::WindingData*> windingReady_{nullptr};
};

}  // namespace unidist
