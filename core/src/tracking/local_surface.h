// Local point projection onto one model, from a hint (the feature and parameters of the last answer): what the
// tracker's local updates are built from. Its cost does not grow with the model: a walk over a mesh's triangle
// neighbours, a point Newton on a NURBS surface; primitives and clouds answer their exact closest point (cheap
// already). Precomputed per model once (the mesh's vertex → triangle lists). Const and thread-safe. Internal.
#pragma once

#include "unidist/model.h"

#include <memory>
#include <vector>

namespace unidist {
class TriangleMesh;
class NurbsModel;
}  // namespace unidist

namespace unidist::tracking {

/// Where on a model a tracked point sits: the model's feature id and surface parameters (SurfacePoint's).
struct Hint {
  int feature = 0;
  Eigen::Vector2d param = Eigen::Vector2d::Zero();
};

/// Work done, for the counters.
struct Work {
  long newton = 0, steps = 0, fallbacks = 0;
};

class LocalSurface {
 public:
  virtual ~LocalSurface() = default;
  static std::unique_ptr<LocalSurface> make(const Model& m);

  const Model& model() const { return *model_; }
  /// The surface point locally closest to q_M (model frame) near the hint, which is updated. Signed like
  /// Model::closestPoint (negative inside a solid). Falls back to the exact global query when the local
  /// method cannot answer (a walk too long, Newton at a degenerate point).
  virtual SurfacePoint project(const Eigen::Vector3d& q_M, Hint& hint, Work& work) const = 0;
  /// The hint of a point found by a global query (closestPoint's feature and parameters).
  virtual Hint hintOf(const SurfacePoint& s) const { return {s.feature, s.param}; }
  /// Whether the model has a vertex graph for the overlap descent to walk (meshes only).
  virtual bool hasVertexGraph() const { return false; }
  /// Mesh only: the vertex of the hint's triangle nearest to p_M, and the vertices sharing a triangle with v.
  virtual int nearestVertex(const Hint&, const Eigen::Vector3d&) const { return -1; }
  virtual void vertexNeighbours(int, std::vector<int>&) const {}
  virtual Eigen::Vector3d vertex(int) const { return Eigen::Vector3d::Zero(); }
  virtual Hint vertexHint(int) const { return {}; }
  /// Mesh only: the mesh, and the triangles sharing a vertex with t (t included).
  virtual const TriangleMesh* mesh() const { return nullptr; }
  virtual void triangleRing(int, std::vector<int>&) const {}

 protected:
  explicit LocalSurface(const Model& m) : model_(&m) {}
  const Model* model_;
};

}  // namespace unidist::tracking
