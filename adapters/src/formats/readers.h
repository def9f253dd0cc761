// The model file readers plugged into the format table of adapters/src/load.cpp (modelFormats()). Each reads
// the whole file, checks it strictly and returns a TriangleMesh, a PointCloud or a NurbsModel; every problem is an
// InputError naming the file and the line ("<path>:<line>: ...") or byte offset ("<path>: byte <n>: ...").
// What each accepts is documented at the top of its source file; why these are hand-written rather than a
// library's is in docs/dependencies.md.
#pragma once

#include "unidist/mesh.h"
#include "unidist/model.h"

#include <memory>
#include <string>
#include <vector>

namespace unidist::formats {

/// Wavefront OBJ: a triangle mesh (polygons fan-triangulated). adapters/src/formats/obj_reader.cpp.
std::shared_ptr<const Model> readObj(const std::string& path);
/// An OBJ file's faces with the group ('o'/'g' statement) each belongs to, unwelded: what convex pieces are
/// made of. Same checks as readObj. Faces before any group belong to a group named "".
struct ObjGroups {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<TriangleMesh::Triangle> triangles;
  std::vector<int> groupOfTriangle;  ///< index into groupNames, one per triangle
  std::vector<std::string> groupNames;
};
ObjGroups readObjGroups(const std::string& path);
/// STL, ASCII or binary (decided by the binary size 84 + 50·n first): a triangle mesh.
std::shared_ptr<const Model> readStl(const std::string& path);
/// PLY, ASCII or binary little/big endian: a triangle mesh when it has faces, else a point cloud.
std::shared_ptr<const Model> readPly(const std::string& path);
/// XYZ point cloud: "x y z" or "x y z nx ny nz" per line.
std::shared_ptr<const Model> readXyz(const std::string& path);

/// unidist NURBS JSON (.unurbs.json): a NurbsModel. adapters/src/formats/unurbs_reader.cpp.
std::shared_ptr<const Model> readUnurbs(const std::string& path);
/// IGES: the rational B-spline surfaces (entity 128) of the file, as an open NurbsModel.
/// adapters/src/formats/iges_reader.cpp.
std::shared_ptr<const Model> readIges(const std::string& path);

/// Builds the mesh; the model's own InputError (e.g. every triangle has zero area) gets "<path>: " in front.
std::shared_ptr<const Model> makeMesh(const std::string& path, std::vector<Eigen::Vector3d> vertices,
                                      std::vector<TriangleMesh::Triangle> triangles);
/// Builds the cloud (normals empty or one per point), prefixing the model's InputError with "<path>: ".
std::shared_ptr<const Model> makeCloud(const std::string& path, std::vector<Eigen::Vector3d> points,
                                       std::vector<Eigen::Vector3d> normals);

}  // namespace unidist::formats
