// Convex pieces as files and specs give them (unidist/adapters/convex_pieces.h): OBJ groups, one-piece meshes,
// box specs, and what a piece set refuses.
#include "scratch_files.h"
#include "unidist/adapters/convex_pieces.h"

namespace unidist::testing {
namespace {

using ConvexPiecesTest = ScratchFiles;

TEST_F(ConvexPiecesTest, ObjGroupsBecomePiecesWithTheirOwnVertices) {
  const std::string path = write("two.obj",
                                 "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"  // shared by both groups
                                 "v 5 0 0\nv 6 0 0\nv 5 1 0\nv 5 0 1\n"
                                 "o first\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"
                                 "g second piece\nf 5 7 6\nf 5 6 8\nf 5 8 7\nf 6 7 8\n");
  const std::vector<PieceSource> pieces = loadConvexPieces(path);
  ASSERT_EQ(pieces.size(), 2u);
  EXPECT_EQ(pieces[0].name, "first");
  EXPECT_EQ(pieces[1].name, "second piece");
  for (const PieceSource& p : pieces) {
    EXPECT_EQ(p.vertices.size(), 4u);  // only the vertices the group's faces use
    EXPECT_EQ(p.triangles.size(), 4u);
  }
  EXPECT_EQ(pieces[1].vertices[0], Eigen::Vector3d(5, 0, 0));
}

TEST_F(ConvexPiecesTest, RepeatedGroupNamesJoinOnePieceAndFacesBeforeAnyGroupFormTheirOwn) {
  const std::string path = write("mixed.obj",
                                 "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                 "f 1 3 2\n"
                                 "g a\nf 1 2 4\n"
                                 "g b\nf 1 4 3\n"
                                 "g a\nf 2 3 4\n");
  const std::vector<PieceSource> pieces = loadConvexPieces(path);
  ASSERT_EQ(pieces.size(), 3u);
  EXPECT_EQ(pieces[0].name, "");
  EXPECT_EQ(pieces[1].name, "a");
  EXPECT_EQ(pieces[1].triangles.size(), 2u);
  EXPECT_EQ(pieces[2].triangles.size(), 1u);
}

TEST_F(ConvexPiecesTest, OtherMeshFilesAreOnePieceAndABoxSpecItsCorners) {
  const std::string stl = write("tet.stl",
                                "solid t\n"
                                "facet normal 0 0 -1\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 1 0 0\nendloop\nendfacet\n"
                                "facet normal 0 -1 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 0 1\nendloop\nendfacet\n"
                                "facet normal -1 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 1\nvertex 0 1 0\nendloop\nendfacet\n"
                                "facet normal 1 1 1\nouter loop\nvertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\nendloop\nendfacet\n"
                                "endsolid t\n");
  const std::vector<PieceSource> mesh = loadConvexPieces(stl);
  ASSERT_EQ(mesh.size(), 1u);
  EXPECT_EQ(mesh[0].vertices.size(), 4u);  // welded by the mesh reader
  EXPECT_EQ(mesh[0].triangles.size(), 4u);

  const std::vector<PieceSource> box = loadConvexPieces("box:hx=1,hy=2,hz=3");
  ASSERT_EQ(box.size(), 1u);
  ASSERT_EQ(box[0].vertices.size(), 8u);
  for (const Eigen::Vector3d& v : box[0].vertices) EXPECT_EQ(v.cwiseAbs(), Eigen::Vector3d(1, 2, 3));
}

TEST_F(ConvexPiecesTest, RoundPrimitivesCloudsAndBrokenFilesAreRefusedByName) {
  EXPECT_NE(errorOf([] { loadConvexPieces("sphere:r=1"); }).find("one group ('o' or 'g') per piece"),
            std::string::npos);
  const std::string cloud = write("c.xyz", "0 0 0\n1 0 0\n0 1 0\n");
  EXPECT_NE(errorOf([&] { loadConvexPieces(cloud); }).find(cloud), std::string::npos);
  const std::string broken = write("bad.obj", "v 0 0 0\no x\nf 1 2 3\n");
  EXPECT_NE(errorOf([&] { loadConvexPieces(broken); }).find(broken + ":3:"), std::string::npos);
}

}  // namespace
}  // namespace unidist::testing
