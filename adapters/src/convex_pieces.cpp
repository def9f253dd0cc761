#include "unidist/adapters/convex_pieces.h"

#include "unidist/adapters/load.h"
#include "unidist/adapters/spec.h"
#include "unidist/mesh.h"
#include "unidist/primitives.h"

#include "formats/readers.h"

#include <algorithm>
#include <cctype>
#include <unordered_map>

namespace unidist {
namespace {

bool isObj(const std::string& path) {
  if (path.size() < 4) return false;
  std::string ext = path.substr(path.size() - 4);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".obj";
}

/// The faces of one group with their vertices renumbered (only the vertices the group uses).
PieceSource pieceOfGroup(const formats::ObjGroups& obj, int group) {
  PieceSource piece;
  piece.name = obj.groupNames[static_cast<std::size_t>(group)];
  std::unordered_map<std::uint32_t, int> local;
  for (std::size_t t = 0; t < obj.triangles.size(); ++t) {
    if (obj.groupOfTriangle[t] != group) continue;
    std::array<int, 3> tri{};
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = obj.triangles[t][static_cast<std::size_t>(k)];
      const auto [it, added] = local.emplace(v, static_cast<int>(piece.vertices.size()));
      if (added) piece.vertices.push_back(obj.vertices[v]);
      tri[static_cast<std::size_t>(k)] = it->second;
    }
    piece.triangles.push_back(tri);
  }
  return piece;
}

PieceSource pieceOfMesh(const TriangleMesh& mesh, const std::string& name) {
  PieceSource piece;
  piece.name = name;
  piece.vertices = mesh.vertices();
  for (const TriangleMesh::Triangle& t : mesh.triangles())
    piece.triangles.push_back({static_cast<int>(t[0]), static_cast<int>(t[1]), static_cast<int>(t[2])});
  return piece;
}

PieceSource pieceOfBox(const Box& box, const std::string& name) {
  PieceSource piece;
  piece.name = name;
  for (int corner = 0; corner < 8; ++corner)
    piece.vertices.push_back(box.halfExtents().cwiseProduct(
        Eigen::Vector3d((corner & 1) ? 1 : -1, (corner & 2) ? 1 : -1, (corner & 4) ? 1 : -1)));
  return piece;
}

}  // namespace

std::vector<PieceSource> loadConvexPieces(const std::string& specOrPath) {
  std::vector<PieceSource> pieces;
  if (!looksLikePrimitiveSpec(specOrPath) && isObj(specOrPath)) {
    const formats::ObjGroups obj = formats::readObjGroups(specOrPath);
    for (int g = 0; g < static_cast<int>(obj.groupNames.size()); ++g) {
      PieceSource piece = pieceOfGroup(obj, g);
      if (!piece.triangles.empty()) pieces.push_back(std::move(piece));
    }
    return pieces;
  }
  const std::shared_ptr<const Model> model = loadModel(specOrPath);
  if (const auto* mesh = dynamic_cast<const TriangleMesh*>(model.get())) {
    pieces.push_back(pieceOfMesh(*mesh, ""));
  } else if (const auto* box = dynamic_cast<const Box*>(model.get())) {
    pieces.push_back(pieceOfBox(*box, "box"));
  } else {
    throw InputError(specOrPath + ": a union of convex pieces is an OBJ with one group ('o' or 'g') per piece, "
                     "another mesh file holding one convex piece, or a box spec (this is a " +
                     toString(model->type()) + ")");
  }
  return pieces;
}

}  // namespace unidist
