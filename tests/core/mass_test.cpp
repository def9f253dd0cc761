// Mass properties: primitives against textbook closed forms and against a voxel integration of their own
// inside() (which catches frame conventions: cone apex up, capsule along z); meshes against an independent
// long-double oracle (canonical-tetrahedron covariance from the origin) and exact polyhedra; NURBS solids
// against the analytic sphere and torus; principal frames of rotated boxes.
#include "unidist/adapters/load.h"
#include "unidist/mass.h"
#include "unidist/mesh.h"
#include "unidist/nurbs.h"
#include "unidist/point_cloud.h"
#include "unidist/primitives.h"

#include "core/mesh_fixtures.h"
#include "core/nurbs_fixtures.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>

namespace {

using namespace unidist;
using Vec = Eigen::Vector3d;
using Mat = Eigen::Matrix3d;
constexpr double kPi = 3.14159265358979323846;

const std::filesystem::path kModels =
    std::filesystem::path(__FILE__).parent_path() / ".." / ".." / ".." / "shared" / "acceptance" / "models";

/// Expected properties with a relative tolerance: volume relative to itself, centre relative to `size`,
/// inertia entries relative to the largest moment.
void expectProps(const MassProperties& got, double volume, const Vec& com, const Mat& inertia, double rel, double size) {
  EXPECT_NEAR(got.volume, volume, rel * volume);
  EXPECT_LE((got.centerOfMass - com).cwiseAbs().maxCoeff(), rel * size) << got.centerOfMass.transpose();
  const double scale = inertia.cwiseAbs().maxCoeff();
  EXPECT_LE((got.inertia - inertia).cwiseAbs().maxCoeff(), rel * scale) << "got\n" << got.inertia << "\nwant\n" << inertia;
}

Mat diag(double a, double b, double c) { return Vec(a, b, c).asDiagonal(); }

// ---- primitives ----------------------------------------------------------------------------------------------

TEST(MassPrimitives, MatchTextbookClosedForms) {
  const double tight = 1e-14;
  {
    const double r = 1.7, m = 4.0 / 3.0 * kPi * std::pow(r, 3), I = 2.0 / 5.0 * m * r * r;
    const MassProperties p = massProperties(Sphere(r));
    expectProps(p, m, Vec::Zero(), diag(I, I, I), tight, r);
    EXPECT_TRUE(p.exact);
  }
  {
    const double a = 1, b = 2, c = 3, m = a * b * c;  // full edge lengths
    expectProps(massProperties(Box(Vec(a, b, c) / 2)), m, Vec::Zero(),
                diag(m / 12 * (b * b + c * c), m / 12 * (a * a + c * c), m / 12 * (a * a + b * b)), tight, 3);
  }
  {
    const double r = 0.5, H = 3, m = kPi * r * r * H;  // cylinder of height H
    expectProps(massProperties(Cylinder(r, H / 2)), m, Vec::Zero(),
                diag(m / 12 * (3 * r * r + H * H), m / 12 * (3 * r * r + H * H), m * r * r / 2), tight, H);
  }
  {
    // Cone of height H: centre of mass H/4 above the base (base at z = −H/2), transverse 3/80 m (4r² + H²).
    const double r = 0.8, H = 2.4, m = kPi * r * r * H / 3, It = 3.0 / 80.0 * m * (4 * r * r + H * H);
    expectProps(massProperties(Cone(r, H / 2)), m, Vec(0, 0, -H / 2 + H / 4), diag(It, It, 3.0 / 10.0 * m * r * r), tight,
                H);
  }
  {
    // Capsule: cylinder of height H plus a ball; transverse m_c(H²/12 + r²/4) + m_s(2r²/5 + H²/4 + 3Hr/8).
    const double r = 0.4, H = 1.6, mc = kPi * r * r * H, ms = 4.0 / 3.0 * kPi * std::pow(r, 3);
    const double It = mc * (H * H / 12 + r * r / 4) + ms * (2 * r * r / 5 + H * H / 4 + 3 * H * r / 8);
    expectProps(massProperties(Capsule(r, H / 2)), mc + ms, Vec::Zero(),
                diag(It, It, mc * r * r / 2 + ms * 2 * r * r / 5), tight, H + 2 * r);
  }
  {
    const double R = 2, a = 0.5, m = 2 * kPi * kPi * R * a * a;
    expectProps(massProperties(Torus(R, a)), m, Vec::Zero(),
                diag(m / 8 * (4 * R * R + 5 * a * a), m / 8 * (4 * R * R + 5 * a * a), m / 4 * (4 * R * R + 3 * a * a)),
                tight, R + a);
  }
}

/// Midpoint-rule integration of the indicator inside() over a grid on the bounds: slow and rough, but it
/// only uses the model's own idea of where its solid is.
MassProperties voxelMass(const Model& m, int n) {
  const Aabb b = m.localBounds();
  const Vec step = (b.max - b.min) / n;
  const double cell = step.prod();
  double v = 0;
  Vec first = Vec::Zero();
  Mat second = Mat::Zero();
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const Vec x = b.min + step.cwiseProduct(Vec(i + 0.5, j + 0.5, k + 0.5));
        if (!m.inside(x)) continue;
        v += cell;
        first += cell * x;
        second += cell * x * x.transpose();
      }
  MassProperties out;
  out.volume = v;
  out.centerOfMass = first / v;
  const Mat C = second - v * out.centerOfMass * out.centerOfMass.transpose();
  out.inertia = C.trace() * Mat::Identity() - C;
  return out;
}

TEST(MassPrimitives, AgreeWithVoxelIntegrationOfTheirOwnSolid) {
  const std::vector<std::shared_ptr<const Model>> models = {
      std::make_shared<Sphere>(0.9),          std::make_shared<Box>(Vec(0.3, 0.7, 1.1)),
      std::make_shared<Capsule>(0.3, 0.9),    std::make_shared<Cylinder>(0.4, 1.2),
      std::make_shared<Cone>(0.7, 1.0),       std::make_shared<Torus>(1.0, 0.35)};
  for (const auto& m : models) {
    SCOPED_TRACE(m->describe());
    const MassProperties exact = massProperties(*m), voxel = voxelMass(*m, 90);
    expectProps(voxel, exact.volume, exact.centerOfMass, exact.inertia, 0.01, m->localBounds().diagonal());
  }
}

TEST(MassPrimitives, HalfSpaceIsRejected) {
  try {
    massProperties(Plane(Vec(0, 0, 1), 0));
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("unbounded"), std::string::npos) << e.what();
  }
}

// ---- meshes ---------------------------------------------------------------------------------------------------

/// Independent oracle for a closed outward soup: tetrahedra from the origin in long double, second moments by
/// the canonical tetrahedron's covariance mapped through each tetrahedron's edge matrix A: det(A)·A·C₀·Aᵀ.
MassProperties oracle(const meshfix::Soup& s) {
  using LMat = Eigen::Matrix<long double, 3, 3>;
  using LVec = Eigen::Matrix<long double, 3, 1>;
  LMat canonical;
  canonical << 2, 1, 1, 1, 2, 1, 1, 1, 2;
  canonical /= 120;
  long double v = 0;
  LVec first = LVec::Zero();
  LMat second = LMat::Zero();
  for (const meshfix::Tri& t : s.triangles) {
    LMat A;
    for (int k = 0; k < 3; ++k) A.col(k) = s.vertices[t[static_cast<std::size_t>(k)]].cast<long double>();
    const long double det = A.determinant();
    v += det / 6;
    first += det / 24 * A.rowwise().sum();
    second += det * A * canonical * A.transpose();
  }
  MassProperties out;
  out.volume = static_cast<double>(v);
  const LVec com = first / v;
  const LMat C = second - v * com * com.transpose();
  out.centerOfMass = com.cast<double>();
  out.inertia = (C.trace() * LMat::Identity() - C).cast<double>();
  return out;
}

void expectMatchesOracle(const meshfix::Soup& s, double rel) {
  const MassProperties want = oracle(s), got = massProperties(meshfix::makeMesh(s));
  EXPECT_TRUE(got.exact);
  expectProps(got, want.volume, want.centerOfMass, want.inertia, rel, meshfix::makeMesh(s).localBounds().diagonal());
}

Eigen::Isometry3d somePose() {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = (Eigen::AngleAxisd(0.7, Vec(1, 2, -0.5).normalized()) * Eigen::AngleAxisd(-1.1, Vec::UnitZ())).matrix();
  X.translation() = Vec(3.5, -2, 7.25);
  return X;
}

meshfix::Soup moved(meshfix::Soup s, const Eigen::Isometry3d& X) {
  for (Vec& v : s.vertices) v = X * v;
  return s;
}

TEST(MassMesh, BoxMeshEqualsTheBoxPrimitive) {
  const Vec h(0.5, 1.25, 2);
  const MassProperties want = massProperties(Box(h));
  const MassProperties got = massProperties(meshfix::makeMesh(meshfix::gridBox(h, 4)));
  expectProps(got, want.volume, want.centerOfMass, want.inertia, 1e-13, 5);
}

TEST(MassMesh, ExactPolyhedra) {
  // Corner tetrahedron (0, e1, e2, e3): V = 1/6, centroid 1/4, ∫x² = 1/60, ∫xy = 1/120 (about the origin).
  const meshfix::Soup tet{{Vec::Zero(), Vec::UnitX(), Vec::UnitY(), Vec::UnitZ()}, {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}};
  Mat secondAtOrigin = Mat::Constant(1.0 / 120);
  secondAtOrigin.diagonal().setConstant(1.0 / 60);
  const Vec c = Vec::Constant(0.25);
  const Mat C = secondAtOrigin - (1.0 / 6) * c * c.transpose();
  expectProps(massProperties(meshfix::makeMesh(tet)), 1.0 / 6, c, C.trace() * Mat::Identity() - C, 1e-14, 1);

  // Octahedron |x| + |y| + |z| <= a: V = 4a³/3, every moment V a²/5.
  const double a = 1.5, V = 4 * a * a * a / 3;
  const meshfix::Soup octa{{{a, 0, 0}, {-a, 0, 0}, {0, a, 0}, {0, -a, 0}, {0, 0, a}, {0, 0, -a}},
                           {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}}};
  expectProps(massProperties(meshfix::makeMesh(octa)), V, Vec::Zero(), diag(V * a * a / 5, V * a * a / 5, V * a * a / 5),
              1e-14, a);
}

TEST(MassMesh, RigidMotionMovesTheCentreAndRotatesTheInertia) {
  const meshfix::Soup cube = meshfix::gridBox(Vec(0.5, 0.5, 0.5), 1);
  const Eigen::Isometry3d X = somePose();
  const MassProperties atOrigin = massProperties(meshfix::makeMesh(cube));
  const MassProperties posed = massProperties(meshfix::makeMesh(moved(cube, X)));
  expectProps(posed, 1, X.translation(), X.linear() * atOrigin.inertia * X.linear().transpose(), 1e-12, 10);
  expectProps(atOrigin, 1, Vec::Zero(), diag(1.0 / 6, 1.0 / 6, 1.0 / 6), 1e-14, 1);
}

TEST(MassMesh, TessellatedSolidsMatchTheOracleAndApproachTheirSmoothShapes) {
  const Eigen::Isometry3d X = somePose();
  expectMatchesOracle(meshfix::icosphere(1.3, 3), 1e-12);
  expectMatchesOracle(moved(meshfix::icosphere(1.3, 3), X), 1e-12);
  expectMatchesOracle(moved(meshfix::torus(2, 0.6, 48, 24), X), 1e-12);

  // The inscribed polyhedra converge to the sphere and torus (second order in the edge length).
  const MassProperties sphere = massProperties(meshfix::makeMesh(meshfix::icosphere(1.3, 5)));
  const MassProperties ball = massProperties(Sphere(1.3));
  expectProps(sphere, ball.volume, Vec::Zero(), ball.inertia, 2e-3, 1.3);
  const MassProperties ring = massProperties(meshfix::makeMesh(meshfix::torus(2, 0.6, 256, 128)));
  const MassProperties torus = massProperties(Torus(2, 0.6));
  expectProps(ring, torus.volume, Vec::Zero(), torus.inertia, 2e-3, 2.6);
}

TEST(MassMesh, InwardOrientedInputGivesTheSameSolid) {
  const meshfix::Soup box = moved(meshfix::gridBox(Vec(0.25, 1, 0.5), 2), somePose());
  const TriangleMesh inward = meshfix::makeMesh(meshfix::reversed(box));
  ASSERT_TRUE(inward.stats().flipped);
  const MassProperties want = oracle(box), got = massProperties(inward);
  expectProps(got, want.volume, want.centerOfMass, want.inertia, 1e-12, 10);
  EXPECT_NEAR(got.volume, 1.0, 1e-12);
}

TEST(MassMesh, OpenMeshAndPointCloudUseTheirBoundsBox) {
  meshfix::Soup open = meshfix::gridBox(Vec(1, 2, 3), 2);
  open.triangles.resize(open.triangles.size() - 2);  // a hole: no inside any more
  const TriangleMesh sheet = meshfix::makeMesh(open);
  ASSERT_FALSE(sheet.isSolid());
  const MassProperties p = massProperties(sheet);
  EXPECT_FALSE(p.exact);
  expectProps(p, 48, Vec::Zero(), diag(48.0 / 12 * (16 + 36), 48.0 / 12 * (4 + 36), 48.0 / 12 * (4 + 16)), 1e-14, 7);

  const PointCloud cloud({Vec(1, 1, 1), Vec(3, 2, 5), Vec(2, 1.5, 2)});
  const MassProperties q = massProperties(cloud);
  EXPECT_FALSE(q.exact);
  expectProps(q, 2 * 1 * 4, Vec(2, 1.5, 3), diag(8.0 / 12 * (1 + 16), 8.0 / 12 * (4 + 16), 8.0 / 12 * (4 + 1)), 1e-14, 5);
}

TEST(MassMesh, FlatStandInIsRejectedNamingTheModel) {
  const PointCloud flat({Vec(0, 0, 0), Vec(1, 0, 0), Vec(0, 1, 0)});
  try {
    massProperties(flat);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(flat.describe()), std::string::npos) << e.what();
  }
}

// ---- NURBS ----------------------------------------------------------------------------------------------------

TEST(MassNurbs, AcceptanceSphereAndTorusMatchTheAnalyticSolids) {
  const std::filesystem::path sphereFile = kModels / "sphere_nurbs.unurbs.json", torusFile = kModels / "torus_nurbs.unurbs.json";
  if (!std::filesystem::exists(sphereFile) || !std::filesystem::exists(torusFile))
    GTEST_SKIP() << "shared acceptance models not found at " << kModels;
  // The files hold the unit sphere and the torus R = 1, r = 0.25, both centred at the origin.
  const MassProperties ball = massProperties(Sphere(1)), ring = massProperties(Torus(1, 0.25));
  const MassProperties sphere = massProperties(*loadModel(sphereFile.string()));
  const MassProperties torus = massProperties(*loadModel(torusFile.string()));
  EXPECT_TRUE(sphere.exact && torus.exact);
  expectProps(sphere, ball.volume, Vec::Zero(), ball.inertia, 1e-12, 1);
  expectProps(torus, ring.volume, Vec::Zero(), ring.inertia, 1e-12, 1.25);
}

TEST(MassNurbs, MovedScaledAndReversedSurfacesStayExact) {
  const Vec centre(40, -3, 12.5);
  const NurbsModel sphere({nurbs_fixtures::sphereSurface(2.5, centre)}, true);
  const MassProperties ball = massProperties(Sphere(2.5));
  expectProps(massProperties(sphere), ball.volume, centre, ball.inertia, 1e-12, 2.5);

  // The same torus with its u direction reversed: Su × Sv points inward and the model says so.
  const NurbsSurface t = nurbs_fixtures::torusSurface(1.5, 0.4);
  std::vector<std::vector<Eigen::Vector4d>> net(static_cast<std::size_t>(t.countU()));
  for (int i = 0; i < t.countU(); ++i)
    for (int j = 0; j < t.countV(); ++j) net[static_cast<std::size_t>(i)].push_back(t.controlPoint(t.countU() - 1 - i, j));
  const NurbsModel reversed({NurbsSurface(2, 2, nurbs_fixtures::circleKnots(), nurbs_fixtures::circleKnots(), net)}, true);
  ASSERT_EQ(reversed.orientation(), -1);
  const MassProperties ring = massProperties(Torus(1.5, 0.4));
  expectProps(massProperties(reversed), ring.volume, Vec::Zero(), ring.inertia, 1e-12, 2);
}

TEST(MassNurbs, OpenSurfaceUsesItsBoundsBox) {
  const NurbsModel tube({nurbs_fixtures::cylinderSurface(0.5, 1)}, false);
  const MassProperties p = massProperties(tube);
  EXPECT_FALSE(p.exact);
  EXPECT_NEAR(p.volume, 1 * 1 * 2, 1e-12);
}

// ---- principal frame ------------------------------------------------------------------------------------------

TEST(MassPrincipal, RotatedBoxMeshGivesItsAxesAndMoments) {
  const Vec h(0.5, 1, 1.5);  // distinct moments: the axes are determined up to sign
  const Eigen::Isometry3d X = somePose();
  const MassProperties props = massProperties(meshfix::makeMesh(moved(meshfix::gridBox(h, 1), X)));
  const double mass = 7.5, V = 8 * h.prod();
  const PrincipalInertia pi = principalInertia(props, mass);
  // Ascending: the axis with the largest extent (z of the box) has the smallest moment.
  const Vec want = mass / 12 * Vec(4 * (h.x() * h.x() + h.y() * h.y()), 4 * (h.x() * h.x() + h.z() * h.z()),
                                   4 * (h.y() * h.y() + h.z() * h.z()));
  EXPECT_LE((pi.moments - want).cwiseAbs().maxCoeff(), 1e-12 * want.maxCoeff()) << pi.moments.transpose();
  EXPECT_NEAR(props.volume, V, 1e-12 * V);
  EXPECT_LE((pi.X_MB.translation() - X.translation()).norm(), 1e-12 * 10);
  const Mat R = pi.X_MB.linear();
  EXPECT_NEAR(R.determinant(), 1, 1e-12);
  EXPECT_LE((R.transpose() * R - Mat::Identity()).cwiseAbs().maxCoeff(), 1e-12);
  // Body axis k is the box's axis (2, 1, 0)[k] in the model frame, either sign.
  const int boxAxis[3] = {2, 1, 0};
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(std::abs(R.col(k).dot(X.linear().col(boxAxis[k]))), 1, 1e-10) << k;
  // The inertia is diagonal in the body frame.
  const Mat inBody = R.transpose() * (mass / V * props.inertia) * R;
  EXPECT_LE((inBody - Mat(pi.moments.asDiagonal())).cwiseAbs().maxCoeff(), 1e-12 * want.maxCoeff());
}

TEST(MassPrincipal, ReflectionIsTurnedIntoARotation) {
  // A symmetric body: every frame is principal, and the solver may hand back a reflection; ours must not.
  for (const auto& m : std::vector<std::shared_ptr<const Model>>{std::make_shared<Sphere>(1), std::make_shared<Cylinder>(1, 2),
                                                                 std::make_shared<Box>(Vec(1, 2, 3))}) {
    const PrincipalInertia pi = principalInertia(massProperties(*m), 2);
    EXPECT_NEAR(pi.X_MB.linear().determinant(), 1, 1e-12) << m->describe();
    EXPECT_TRUE((pi.moments.array() >= 0).all());
  }
}

TEST(MassPrincipal, RejectsBadMass) {
  const MassProperties p = massProperties(Sphere(1));
  EXPECT_THROW(principalInertia(p, 0), InputError);
  EXPECT_THROW(principalInertia(p, -1), InputError);
  EXPECT_THROW(principalInertia(p, std::nan("")), InputError);
  EXPECT_THROW(principalInertia(MassProperties{}, 1), InputError);  // zero volume
}

}  // namespace
