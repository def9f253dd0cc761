#include "raster_fixtures.h"
#include "unidist/raster/convex_union.h"

#include <gtest/gtest.h>

#include <random>

using unidist::InputError;
using unidist::raster::convexHull;
using Vec = Eigen::Vector3d;

TEST(RasterConvexHull, CubeHasSixMergedFacetsAndOutwardTriangles) {
  std::vector<Vec> points;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> inside(-0.9, 0.9);
  for (int c = 0; c < 8; ++c) points.emplace_back((c & 1) ? 1 : -1, (c & 2) ? 1 : -1, (c & 4) ? 1 : -1);
  for (int k = 0; k < 50; ++k) points.emplace_back(inside(rng), inside(rng), inside(rng));
  const auto hull = convexHull(points);
  EXPECT_EQ(hull.vertices.size(), 8u);
  EXPECT_EQ(hull.planes.size(), 6u);  // qhull triangulates nothing: coplanar triangles share one plane
  EXPECT_EQ(hull.triangles.size(), 12u);
  ASSERT_EQ(hull.triangleFacet.size(), hull.triangles.size());
  for (std::size_t v = 0; v < hull.vertices.size(); ++v)
    EXPECT_EQ(hull.vertices[v], points[static_cast<std::size_t>(hull.sourceIndex[v])]);
  for (std::size_t t = 0; t < hull.triangles.size(); ++t) {
    const auto& tri = hull.triangles[t];
    const Vec a = hull.vertices[tri[0]], b = hull.vertices[tri[1]], c = hull.vertices[tri[2]];
    const Vec n = (b - a).cross(c - a).normalized();
    const Eigen::Vector4d& plane = hull.planes[static_cast<std::size_t>(hull.triangleFacet[t])];
    EXPECT_NEAR(n.dot(plane.head<3>()), 1.0, 1e-12);  // counter-clockwise seen from outside
    EXPECT_NEAR(plane.head<3>().dot(a) + plane.w(), 0.0, 1e-12);
  }
  for (const auto& plane : hull.planes) {
    EXPECT_NEAR(plane.head<3>().norm(), 1.0, 1e-12);
    EXPECT_NEAR(plane.w(), -1.0, 1e-12);  // unit cube faces at distance 1 from the centre
  }
}

TEST(RasterConvexHull, BadInputNamesTheProblem) {
  const std::vector<Vec> three{Vec(0, 0, 0), Vec(1, 0, 0), Vec(0, 1, 0)};
  EXPECT_THROW(convexHull(three), InputError);
  const std::vector<Vec> flat{Vec(0, 0, 0), Vec(1, 0, 0), Vec(0, 1, 0), Vec(1, 1, 0), Vec(0.3, 0.2, 0)};
  try {
    convexHull(flat);
    FAIL() << "a flat set must be rejected";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("flat"), std::string::npos) << e.what();
  }
  const std::vector<Vec> nan{Vec(0, 0, 0), Vec(1, 0, 0), Vec(0, 1, 0), Vec(0, 0, std::nan(""))};
  EXPECT_THROW(convexHull(nan), InputError);
  const std::vector<Vec> same(6, Vec(1, 2, 3));
  EXPECT_THROW(convexHull(same), InputError);
}
