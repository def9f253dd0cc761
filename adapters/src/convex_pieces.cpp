#include "unidist/adapters/convex_pieces.h"

#include "unidist/adapters/load.h"
#include "unidist/adapters/spec.h"
#include "unidist/mesh.h"
#include "unidist/primitives.h"

#include "formats/readers.h"

#include <algorithm>
#include <unordered_map>

namespace unidist {
namespace {

bool isObj(const std::string& path) {
  const ModelFormat* format = findModelFormat(path);
  return format && format->read == &formats::readObj;
}

/// One piece per non-empty group, each with its faces' vertices renumbered (only the vertices it uses); one pass
/// over the triangles.
std::vector<PieceSource> piecesOfGroups(const formats::ObjGroups& obj) {
  std::vector<PieceSource> pieces(obj.groupNames.size());
  std::vector<std::unordered_map<std::uint32_t, int>> local(obj.groupNames.size());
  for (std::size_t t = 0; t < obj.triangles.size(); ++t) {
    const auto group = static_cast<std::size_t>(obj.groupOfTriangle[t]);
    PieceSource& piece = pieces[group];
    std::array<int, 3> tri{};
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t v = obj.triangles[t][k];
      const auto [it, added] = local[group].emplace(v, static_cast<int>(piece.vertices.size()));
      if (added) piece.vertices.push_back(obj.vertices[v]);
      tri[k] = it->second;
    }
    piece.triangles.push_back(tri);
  }
  for (std::size_t g = 0; g < pieces.size(); ++g) pieces[g].name = obj.groupNames[g];
  pieces.erase(std::remove_if(pieces.begin(), pieces.end(), [](const PieceSource& p) { return p.triangles.empty(); }),
               pieces.end());
  return pieces;
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
  if (!looksLikePrimitiveSpec(specOrPath) && isObj(specOrPath)) return piecesOfGroups(formats::readObjGroups(specOrPath));
  std::vector<PieceSource> pieces;
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
