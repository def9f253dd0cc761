// Inputs the fuzz targets (tests/fuzz/, docs/reliability.md) found a problem with, kept as regressions: each
// must now give a valid model or an InputError naming the cause, as every input must.
#include "error_of.h"
#include "scratch_files.h"
#include "unidist/adapters/load.h"
#include "unidist/adapters/spec.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace unidist {
namespace {

using unidist::testing::errorOf;
using FuzzRegressions = unidist::testing::ScratchFiles;

// fuzz_spec: finite sizes whose bounding box diagonal overflows gave a model with an infinite bounding sphere
// (and so an infinite default tolerance, "certified (tolerance inf)").
TEST(FuzzRegressionsSpec, SizeWhoseExtentOverflowsIsRefused) {
  EXPECT_NE(errorOf([] { parsePrimitiveSpec("sphere:r=1e308"); }).find("sphere: too large"), std::string::npos);
  EXPECT_NE(errorOf([] { parsePrimitiveSpec("box:hx=1,hy=1e308,hz=1e308"); }).find("box: too large"),
            std::string::npos);
  // Large but representable: the diagonal (about 3.5e300) is finite, so is the bounding sphere.
  const auto big = parsePrimitiveSpec("sphere:r=1e300");
  EXPECT_TRUE(std::isfinite(big->localBounds().diagonal()));
  EXPECT_TRUE(std::isfinite(big->localBoundingSphere().radius));
  EXPECT_NO_THROW(parsePrimitiveSpec("plane:nx=0,ny=0,nz=1,d=1e300"));  // unbounded by design
}

// The same through the file readers: coordinates of ±1e308 are finite, but meshes and clouds keep float boxes in
// their hierarchies, so they refuse coordinates beyond ±1e30 by name.
TEST_F(FuzzRegressions, FileWhoseCoordinatesOverflowTheHierarchyIsRefused) {
  expectLoadError("huge.obj", "v 1e308 0 0\nv -1e308 0 0\nv 0 1e308 0\nv 0 0 1e308\nf 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n",
                  ": mesh: vertex 0", "beyond +-1e30");
  expectLoadError("huge.xyz", "1e308 0 0\n-1e308 0 0\n", ": point cloud: point 0", "beyond +-1e30");
}

// fuzz_xyz: coordinates up to 1.6e58 became infinite float boxes in the point hierarchy, and a NaN bin index
// (undefined behaviour) in its split. Now refused when the cloud is made.
TEST(FuzzRegressionsFiles, CloudBeyondFloatRangeIsRefused) {
  const std::string path = std::string(UNIDIST_FUZZ_DATA_DIR) + "/xyz_bvh_nan_centroid.xyz";
  EXPECT_NE(errorOf([&] { loadModel(path); }).find("beyond +-1e30"), std::string::npos);
}

// fuzz_unurbs, fuzz_iges: loading and what the fuzz targets ask of a model (tests/fuzz/fuzz_common.h) took more
// than libFuzzer's 10 s: a corrupted rational sphere of radius 1e4 whose closest point to a point near its centre
// tied on every subpatch (now 2.4 ms, the Bernstein bound of core/src/nurbs/bernstein_bound.h), and an IGES
// surface (now 0.2 s). Each must answer with finite values.
TEST(FuzzRegressionsFiles, TimeoutInputsAnswer) {
  for (const char* name : {"unurbs_timeout.unurbs.json", "iges_timeout.igs"}) {
    SCOPED_TRACE(name);
    const std::shared_ptr<const Model> m = loadModel(std::string(UNIDIST_FUZZ_DATA_DIR) + "/" + name);
    const SurfacePoint p = m->closestPoint(Eigen::Vector3d(0.31, -0.72, 1.13));
    EXPECT_TRUE(p.point.allFinite() && p.normal.allFinite() && std::isfinite(p.signedDistance));
    EXPECT_TRUE(m->support(Eigen::Vector3d(0.6, 0.0, -0.8)).allFinite());
  }
}

}  // namespace
}  // namespace unidist
