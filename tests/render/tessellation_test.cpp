// The display tessellation against the exact surfaces: vertices on the surface, every point of every triangle
// within the stated chordal error (2 × relativeChordError × the largest radius), triangles facing outward, and
// area and volume approaching the exact values as the error shrinks.
#include "unidist/adapters/load.h"
#include "unidist/mesh.h"
#include "unidist/point_cloud.h"
#include "unidist/primitives.h"
#include "unidist/render/display_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>

namespace {

using unidist::render::DisplayMesh;
using unidist::render::TessellationOptions;
using unidist::render::tessellate;

constexpr double kPi = 3.14159265358979323846;

struct Measure {
  double area = 0, volume = 0;
};

Measure measure(const DisplayMesh& m) {
  Measure out;
  for (std::size_t t = 0; t < m.triangles.size(); t += 3) {
    const Eigen::Vector3d &a = m.positions[m.triangles[t]], &b = m.positions[m.triangles[t + 1]],
                          &c = m.positions[m.triangles[t + 2]];
    out.area += 0.5 * (b - a).cross(c - a).norm();
    out.volume += a.dot(b.cross(c)) / 6;  // divergence theorem over outward triangles
  }
  return out;
}

/// Largest |signed distance| to the model over the vertices and over a barycentric grid on every triangle, and
/// whether every triangle faces the way the surface's normal points.
struct Deviation {
  double vertices = 0, triangles = 0;
  int inward = 0;
};

Deviation deviation(const unidist::Model& model, const DisplayMesh& m) {
  Deviation out;
  for (const Eigen::Vector3d& p : m.positions)
    out.vertices = std::max(out.vertices, std::abs(model.closestPoint(p).signedDistance));
  constexpr int kGrid = 6;
  for (std::size_t t = 0; t < m.triangles.size(); t += 3) {
    const Eigen::Vector3d &a = m.positions[m.triangles[t]], &b = m.positions[m.triangles[t + 1]],
                          &c = m.positions[m.triangles[t + 2]];
    for (int i = 0; i <= kGrid; ++i)
      for (int j = 0; i + j <= kGrid; ++j) {
        const Eigen::Vector3d p = a + (b - a) * i / kGrid + (c - a) * j / kGrid;
        out.triangles = std::max(out.triangles, std::abs(model.closestPoint(p).signedDistance));
      }
    const Eigen::Vector3d centroid = (a + b + c) / 3;
    if ((b - a).cross(c - a).dot(model.closestPoint(centroid).normal) <= 0) ++out.inward;
  }
  return out;
}

struct PrimitiveCase {
  const char* name;
  std::shared_ptr<const unidist::Model> model;
  double largestRadius, area, volume;
};

std::vector<PrimitiveCase> primitives() {
  const double slant = std::hypot(0.6, 2 * 0.9);
  return {
      {"sphere", std::make_shared<unidist::Sphere>(1.3), 1.3, 4 * kPi * 1.69, 4 * kPi * 1.3 * 1.69 / 3},
      {"capsule", std::make_shared<unidist::Capsule>(0.5, 0.8), 0.5, 4 * kPi * 0.25 + 2 * kPi * 0.5 * 1.6,
       4 * kPi * 0.125 / 3 + kPi * 0.25 * 1.6},
      {"cylinder", std::make_shared<unidist::Cylinder>(0.7, 0.4), 0.7, 2 * kPi * 0.7 * 0.8 + 2 * kPi * 0.49,
       kPi * 0.49 * 0.8},
      {"cone", std::make_shared<unidist::Cone>(0.6, 0.9), 0.6, kPi * 0.6 * slant + kPi * 0.36, kPi * 0.36 * 1.8 / 3},
      {"torus", std::make_shared<unidist::Torus>(1.0, 0.3), 1.3, 4 * kPi * kPi * 0.3, 2 * kPi * kPi * 0.09},
      {"box", std::make_shared<unidist::Box>(Eigen::Vector3d(0.5, 1, 1.5)), 0, 2 * (1 * 2 + 2 * 3 + 1 * 3), 6},
  };
}

TEST(Tessellation, PrimitivesLieWithinTheStatedChordalError) {
  for (const double e : {1e-2, 2e-3}) {
    TessellationOptions options;
    options.relativeChordError = e;
    for (const PrimitiveCase& c : primitives()) {
      SCOPED_TRACE(std::string(c.name) + " at relative chord error " + std::to_string(e));
      const DisplayMesh m = tessellate(*c.model, options);
      ASSERT_GT(m.triangleCount(), 0u);
      ASSERT_EQ(m.normals.size(), m.positions.size());
      for (const Eigen::Vector3d& n : m.normals) EXPECT_NEAR(n.norm(), 1, 1e-12);
      const Deviation d = deviation(*c.model, m);
      EXPECT_LE(d.vertices, 1e-12);
      EXPECT_LE(d.triangles, 2 * e * c.largestRadius + 1e-12);
      EXPECT_EQ(d.inward, 0);
    }
  }
}

TEST(Tessellation, AreaAndVolumeApproachTheExactValues) {
  for (const PrimitiveCase& c : primitives()) {
    SCOPED_TRACE(c.name);
    double previousError = std::numeric_limits<double>::infinity();
    for (const double e : {1e-2, 1e-3, 1e-4}) {
      TessellationOptions options;
      options.relativeChordError = e;
      const Measure m = measure(tessellate(*c.model, options));
      const double areaError = std::abs(m.area / c.area - 1), volumeError = std::abs(m.volume / c.volume - 1);
      EXPECT_LE(areaError, 4 * e);
      EXPECT_LE(volumeError, 4 * e);
      if (c.largestRadius > 0) {  // curved: the error shrinks with the chords
        EXPECT_LT(areaError, previousError);
        previousError = areaError;
      } else {
        EXPECT_LE(areaError, 1e-14);
        EXPECT_LE(volumeError, 1e-14);
      }
    }
  }
}

TEST(Tessellation, SegmentsFollowTheChordError) {
  EXPECT_EQ(unidist::render::segmentsPerCircle(0.25), 8);  // clamped below
  const int n = unidist::render::segmentsPerCircle(2e-3);
  EXPECT_EQ(n % 4, 0);
  EXPECT_LE(1 - std::cos(kPi / n), 2e-3);
  EXPECT_GT(1 - std::cos(kPi / (n - 4)), 2e-3);  // no more chords than needed (to the multiple of 4)
  for (const double bad : {0.0, -1.0, 0.5, std::nan("")})
    EXPECT_THROW(unidist::render::segmentsPerCircle(bad), unidist::InputError);
}

TEST(Tessellation, NurbsBallWithinTheChordalError) {
  const auto ball = unidist::loadModel(UNIDIST_SCENES_DIR "/ball_r150.unurbs.json");
  TessellationOptions options;
  options.relativeChordError = 2e-3;
  const DisplayMesh m = tessellate(*ball, options);
  ASSERT_GT(m.triangleCount(), 100u);
  const Deviation d = deviation(*ball, m);
  EXPECT_LE(d.vertices, 1e-9 * 150);
  EXPECT_LE(d.triangles, 2 * 2e-3 * 150);
  EXPECT_EQ(d.inward, 0);
  const Measure area = measure(m);
  EXPECT_NEAR(area.area / (4 * kPi * 150 * 150), 1, 8e-3);
  EXPECT_NEAR(area.volume / (4 * kPi * 150 * 150 * 150 / 3), 1, 8e-3);
}

TEST(Tessellation, MeshesAreDrawnAsTheyAre) {
  const unidist::TriangleMesh tetra({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}});
  const DisplayMesh m = tessellate(tetra);
  ASSERT_EQ(m.triangleCount(), 4u);
  const Deviation d = deviation(tetra, m);
  EXPECT_LE(d.triangles, 1e-15);
  EXPECT_EQ(d.inward, 0);
  EXPECT_NEAR(measure(m).volume, 1.0 / 6, 1e-15);
  for (std::size_t i = 0; i < m.positions.size(); ++i)
    EXPECT_EQ(m.normals[i], tetra.faceNormal(static_cast<int>(i / 3)));  // flat shading
}

TEST(Tessellation, PointCloudsAreDots) {
  const unidist::PointCloud cloud({{1, 0, 0}, {-1, 0, 0}, {0, 2, 0}});
  const DisplayMesh m = tessellate(cloud);
  EXPECT_EQ(m.triangleCount(), 0u);
  ASSERT_EQ(m.points, cloud.points());
  ASSERT_EQ(m.pointNormals.size(), 3u);
  EXPECT_TRUE(m.pointNormals[0].isApprox(Eigen::Vector3d(1, -2.0 / 3, 0).normalized()));  // away from the centroid
}

TEST(Tessellation, HalfSpaceIsASquareAroundTheCentre) {
  const unidist::Plane floor(Eigen::Vector3d(0, 0, 2), 4);  // z <= 2
  TessellationOptions options;
  options.planeCentre = Eigen::Vector3d(3, -1, 10);
  options.planeHalfExtent = 5;
  const DisplayMesh m = tessellate(floor, options);
  ASSERT_EQ(m.triangleCount(), 2u);
  EXPECT_NEAR(measure(m).area, 100, 1e-12);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : m.positions) {
    EXPECT_NEAR(p.z(), 2, 1e-12);
    mean += p / 4;
  }
  EXPECT_TRUE(mean.isApprox(Eigen::Vector3d(3, -1, 2), 1e-12));
  EXPECT_EQ(m.linePoints.size(), 4u * 9);
  for (const Eigen::Vector3d& n : m.normals) EXPECT_EQ(n, Eigen::Vector3d::UnitZ());
  options.planeHalfExtent = 0;
  EXPECT_THROW(tessellate(floor, options), unidist::InputError);
}

}  // namespace
