// The OBJ-groups loader of convex pieces (unidist/adapters/convex_pieces.h): every piece has vertices, and
// every face index points into its own piece's vertices, all finite.
#include "fuzz_common.h"
#include "unidist/adapters/convex_pieces.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace unidist::fuzz;
  if (size > kMaxInputBytes) return -1;
  static ScratchFile file(".obj");
  const std::string& path = file.write(data, size);
  expectValidOrInputError([&] {
    for (const unidist::PieceSource& piece : unidist::loadConvexPieces(path)) {
      if (piece.vertices.empty()) finding("a piece without vertices");
      for (const Eigen::Vector3d& v : piece.vertices) requireFinite(v.allFinite(), "piece vertex");
      for (const std::array<int, 3>& t : piece.triangles)
        for (int i : t)
          if (i < 0 || i >= static_cast<int>(piece.vertices.size())) finding("piece face index out of range");
    }
  });
  return 0;
}
