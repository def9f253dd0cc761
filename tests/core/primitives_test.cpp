// Primitives against truths written here from the textbook formulas, never from the code under test:
// signed distance functions, parametric surfaces with their normals, support values. Every family runs at
// scales 1e-4, 1 and 1e4 with relative tolerances, on seeded random points (inside, outside, near and on
// the surface, on edges and axes) and on the degenerate points that primitives.h documents.
#include "unidist/primitives.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;
using unidist::InputError;
using unidist::Model;
using unidist::SurfaceCell;
using unidist::SurfacePoint;

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kPi = 3.14159265358979323846;
const double kScales[] = {1e-4, 1.0, 1e4};
// Random cases per shape and scale; an unoptimised build runs fewer, never none.
// Likewise the parameter grid of the brute-force oracles (grid² samples per face).
#ifdef NDEBUG
constexpr int kRandomCases = 2000;
constexpr int kGrid = 150;
#else
constexpr int kRandomCases = 300;
constexpr int kGrid = 40;
#endif

// ---------------------------------------------------------------------------------------------------
// Independent truths.

/// One parameter rectangle of the surface, in the convention each primitive documents for its cells.
struct FaceDomain {
  double u0, u1, v0, v1;
};

struct Truth {
  std::string name;  ///< describe() of the model: a label for failure messages only
  std::shared_ptr<Model> model;
  double size = 1;    ///< length scale for relative tolerances (bounding radius)
  double finest = 1;  ///< smallest radius of curvature (a thin tube turns rounding into larger angles)
  Vector3d extent;    ///< half extents of the bounding box, written independently of localBounds()
  bool convex = true;
  std::function<double(const Vector3d&)> sdf;            ///< exact signed distance
  std::function<Vector3d(int, double, double)> surface;  ///< (face, u, v) -> surface point
  std::function<Vector3d(int, double, double)> normal;   ///< outward unit normal there
  std::vector<FaceDomain> faces;
  std::function<double(const Vector3d&)> supportValue;  ///< max over the solid of dir·x
  std::function<Vector3d(const Vector3d&)> tubeNormal;  ///< torus only: normal from the point alone
};

double hypot3(const Vector3d& v) { return std::hypot(std::hypot(v.x(), v.y()), v.z()); }

/// Distance from p to segment ab in the plane.
double segmentDistance2(const Vector2d& p, const Vector2d& a, const Vector2d& b) {
  const Vector2d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

Truth sphereTruth(double r) {
  Truth t;
  t.model = std::make_shared<unidist::Sphere>(r);
  t.size = r;
  t.finest = r;
  t.extent = Vector3d::Constant(r);
  t.sdf = [r](const Vector3d& q) { return hypot3(q) - r; };
  t.normal = [](int, double lon, double lat) {
    return Vector3d(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat));
  };
  t.surface = [r, n = t.normal](int f, double u, double v) { return Vector3d(r * n(f, u, v)); };
  t.faces = {{-kPi, kPi, -kPi / 2, kPi / 2}};
  t.supportValue = [r](const Vector3d& d) { return r * d.norm(); };
  return t;
}

Truth boxTruth(const Vector3d& h) {
  Truth t;
  t.model = std::make_shared<unidist::Box>(h);
  t.size = h.norm();
  t.finest = t.size;
  t.extent = h;
  // The classic formula: outside part |max(|q|-h, 0)|, inside part min(max_i(|q_i|-h_i), 0).
  t.sdf = [h](const Vector3d& q) {
    const Vector3d d = q.cwiseAbs() - h;
    return d.cwiseMax(0.0).norm() + std::min(d.maxCoeff(), 0.0);
  };
  // Face f: axis f/2, + side for even f; (u, v) = the other two coordinates in increasing axis order.
  t.surface = [h](int f, double u, double v) {
    const int a = f / 2, b = a == 0 ? 1 : 0, c = a == 2 ? 1 : 2;
    Vector3d p;
    p[a] = f % 2 == 0 ? h[a] : -h[a];
    p[b] = u;
    p[c] = v;
    return p;
  };
  t.normal = [](int f, double, double) {
    Vector3d n = Vector3d::Zero();
    n[f / 2] = f % 2 == 0 ? 1 : -1;
    return n;
  };
  for (int f = 0; f < 6; ++f) {
    const int a = f / 2, b = a == 0 ? 1 : 0, c = a == 2 ? 1 : 2;
    t.faces.push_back({-h[b], h[b], -h[c], h[c]});
  }
  t.supportValue = [h](const Vector3d& d) { return d.cwiseAbs().dot(h); };
  return t;
}

Truth capsuleTruth(double r, double h) {
  Truth t;
  t.model = std::make_shared<unidist::Capsule>(r, h);
  t.size = r + h;
  t.finest = r;
  t.extent = Vector3d(r, r, r + h);
  t.sdf = [r, h](const Vector3d& q) { return hypot3(Vector3d(q.x(), q.y(), q.z() - std::clamp(q.z(), -h, h))) - r; };
  // Face 0: band (angle, z). Faces 1 / 2: hemispheres about (0,0,±h), (angle, latitude).
  t.normal = [](int f, double u, double v) {
    if (f == 0) return Vector3d(std::cos(u), std::sin(u), 0);
    return Vector3d(std::cos(v) * std::cos(u), std::cos(v) * std::sin(u), std::sin(v));
  };
  t.surface = [r, h, n = t.normal](int f, double u, double v) {
    if (f == 0) return Vector3d(r * std::cos(u), r * std::sin(u), v);
    return Vector3d(Vector3d(0, 0, f == 1 ? h : -h) + r * n(f, u, v));
  };
  t.faces = {{-kPi, kPi, -h, h}, {-kPi, kPi, 0, kPi / 2}, {-kPi, kPi, -kPi / 2, 0}};
  t.supportValue = [r, h](const Vector3d& d) { return h * std::abs(d.z()) + r * d.norm(); };
  return t;
}

/// Signed distance to a solid of revolution whose (rho, z) profile is a convex polygon with one edge on
/// the axis: the distance to the other edges, negative inside.
double revolvedSdf(const Vector3d& q, const std::vector<Vector2d>& profile, bool inside) {
  const Vector2d p(std::hypot(q.x(), q.y()), q.z());
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < profile.size(); ++i)
    best = std::min(best, segmentDistance2(p, profile[i], profile[i + 1]));
  return inside ? -best : best;
}

Truth cylinderTruth(double r, double h) {
  Truth t;
  t.model = std::make_shared<unidist::Cylinder>(r, h);
  t.size = r + h;
  t.finest = t.size;
  t.extent = Vector3d(r, r, h);
  t.sdf = [r, h](const Vector3d& q) {
    const bool in = std::abs(q.z()) < h && std::hypot(q.x(), q.y()) < r;
    return revolvedSdf(q, {{0, h}, {r, h}, {r, -h}, {0, -h}}, in);
  };
  // Face 0: side (angle, z); 1 / 2: top / bottom disc (angle, rho).
  t.surface = [r, h](int f, double u, double v) {
    if (f == 0) return Vector3d(r * std::cos(u), r * std::sin(u), v);
    return Vector3d(v * std::cos(u), v * std::sin(u), f == 1 ? h : -h);
  };
  t.normal = [](int f, double u, double) {
    return f == 0 ? Vector3d(std::cos(u), std::sin(u), 0) : Vector3d(0, 0, f == 1 ? 1 : -1);
  };
  t.faces = {{-kPi, kPi, -h, h}, {-kPi, kPi, 0, r}, {-kPi, kPi, 0, r}};
  t.supportValue = [r, h](const Vector3d& d) { return r * std::hypot(d.x(), d.y()) + h * std::abs(d.z()); };
  return t;
}

Truth coneTruth(double r, double h) {
  Truth t;
  t.model = std::make_shared<unidist::Cone>(r, h);
  t.size = r + h;
  t.finest = t.size;
  t.extent = Vector3d(r, r, h);
  t.sdf = [r, h](const Vector3d& q) {
    const double rho = std::hypot(q.x(), q.y());
    const bool in = q.z() > -h && rho < r * (h - q.z()) / (2 * h);
    return revolvedSdf(q, {{0, h}, {r, -h}, {0, -h}}, in);
  };
  // Face 0: side (angle, t = slant fraction from the apex); 1: base disc (angle, rho).
  t.surface = [r, h](int f, double u, double v) {
    if (f == 0) return Vector3d(v * r * std::cos(u), v * r * std::sin(u), h - 2 * h * v);
    return Vector3d(v * std::cos(u), v * std::sin(u), -h);
  };
  t.normal = [r, h](int f, double u, double) {
    if (f == 1) return Vector3d(0, 0, -1);
    const double L = std::hypot(r, 2 * h);
    return Vector3d(2 * h / L * std::cos(u), 2 * h / L * std::sin(u), r / L);
  };
  t.faces = {{-kPi, kPi, 0, 1}, {-kPi, kPi, 0, r}};
  t.supportValue = [r, h](const Vector3d& d) { return std::max(h * d.z(), r * std::hypot(d.x(), d.y()) - h * d.z()); };
  return t;
}

Truth torusTruth(double R, double r) {
  Truth t;
  t.model = std::make_shared<unidist::Torus>(R, r);
  t.size = R + r;
  t.finest = r;
  t.extent = Vector3d(R + r, R + r, r);
  t.convex = false;
  t.sdf = [R, r](const Vector3d& q) { return std::hypot(std::hypot(q.x(), q.y()) - R, q.z()) - r; };
  t.normal = [](int, double th, double ph) {
    return Vector3d(std::cos(ph) * std::cos(th), std::cos(ph) * std::sin(th), std::sin(ph));
  };
  t.surface = [R, r, n = t.normal](int f, double th, double ph) {
    return Vector3d(Vector3d(R * std::cos(th), R * std::sin(th), 0) + r * n(f, th, ph));
  };
  t.faces = {{-kPi, kPi, -kPi, kPi}};
  // The hull's support: the centre circle's plus r·|d|.
  t.supportValue = [R, r](const Vector3d& d) { return R * std::hypot(d.x(), d.y()) + r * d.norm(); };
  t.tubeNormal = [R, r](const Vector3d& p) {
    const double rho = std::hypot(p.x(), p.y());
    return Vector3d((p - Vector3d(R * p.x() / rho, R * p.y() / rho, 0)) / r);
  };
  return t;
}

/// Every solid primitive at one scale, with sizes that are neither equal nor powers of two, plus a cube
/// (face ties), a flat cylinder and cone (nearest feature a disc) and a thin torus.
std::vector<Truth> allShapes(double s) {
  std::vector<Truth> shapes = {
      sphereTruth(0.7 * s),
      boxTruth(Vector3d(0.3, 0.6, 1.8) * s),
      boxTruth(Vector3d(1, 1, 1) * s),  // every face ties at the centre
      capsuleTruth(0.4 * s, 0.9 * s),
      cylinderTruth(0.5 * s, 1.3 * s),
      cylinderTruth(2.0 * s, 0.15 * s),  // flat: inside, the discs are nearest
      coneTruth(0.6 * s, 1.1 * s),
      coneTruth(2.0 * s, 0.25 * s),  // flat: inside, the base is often nearest
      torusTruth(1.2 * s, 0.35 * s),
      torusTruth(1.0 * s, 0.01 * s),  // thin tube
  };
  for (Truth& t : shapes) t.name = t.model->describe();
  return shapes;
}

/// Rounding allowance: a few ulps of the shape's size and of the query point's magnitude.
double tolerance(const Truth& t, const Vector3d& q) { return 16 * kEps * (t.size + q.norm()); }

bool finite(const SurfacePoint& s) {
  return s.point.allFinite() && s.normal.allFinite() && std::isfinite(s.signedDistance) && s.param.allFinite();
}

// ---------------------------------------------------------------------------------------------------
// Point generators.

Vector3d uniformIn(std::mt19937_64& rng, const Vector3d& halfExtent) {
  std::uniform_real_distribution<double> u(-1, 1);
  return Vector3d(u(rng), u(rng), u(rng)).cwiseProduct(halfExtent);
}

struct SurfaceSample {
  Vector3d point, normal;
};

SurfaceSample sampleSurface(const Truth& t, std::mt19937_64& rng) {
  std::uniform_int_distribution<int> pickFace(0, static_cast<int>(t.faces.size()) - 1);
  std::uniform_real_distribution<double> unit(0, 1);
  const int f = pickFace(rng);
  const FaceDomain& d = t.faces[f];
  const double u = d.u0 + (d.u1 - d.u0) * unit(rng), v = d.v0 + (d.v1 - d.v0) * unit(rng);
  return {t.surface(f, u, v), t.normal(f, u, v)};
}

/// A (kGrid+1)² grid of parameter samples on every face; `gap` gets the largest distance between grid
/// neighbours, so every surface point lies within gap of some sample.
std::vector<Vector3d> denseSamples(const Truth& t, double& gap) {
  std::vector<Vector3d> samples;
  gap = 0;
  for (std::size_t f = 0; f < t.faces.size(); ++f) {
    const FaceDomain& d = t.faces[f];
    const auto at = [&](int i, int j) {
      return t.surface(static_cast<int>(f), d.u0 + (d.u1 - d.u0) * i / kGrid, d.v0 + (d.v1 - d.v0) * j / kGrid);
    };
    for (int i = 0; i <= kGrid; ++i)
      for (int j = 0; j <= kGrid; ++j) {
        const Vector3d p = at(i, j);
        if (i > 0) gap = std::max(gap, (p - at(i - 1, j)).norm());
        if (j > 0) gap = std::max(gap, (p - at(i, j - 1)).norm());
        samples.push_back(p);
      }
  }
  return samples;
}

/// Points of every kind for one shape: inside and around the box, far away, near the surface on both
/// sides (offsets from 1e-12 to 0.3 of the size), and exactly on the surface.
std::vector<Vector3d> queryPoints(const Truth& t, std::mt19937_64& rng, int count) {
  std::vector<Vector3d> pts;
  std::uniform_real_distribution<double> unit(0, 1);
  for (int i = 0; i < count; ++i) pts.push_back(uniformIn(rng, 1.6 * t.extent));
  for (int i = 0; i < count / 4; ++i) pts.push_back(uniformIn(rng, 60 * t.extent));
  for (int i = 0; i < count; ++i) {
    const SurfaceSample s = sampleSurface(t, rng);
    const double offset = t.size * std::pow(10.0, -12 + 11.5 * unit(rng)) * (unit(rng) < 0.5 ? -1 : 1);
    pts.push_back(s.point + offset * s.normal);
    if (i % 4 == 0) pts.push_back(s.point);
  }
  return pts;
}

// ---------------------------------------------------------------------------------------------------
// The checks every answer must pass.

/// For a convex solid, `n` is an outward normal at surface point p exactly when p maximises n·x. A normal
/// rebuilt from q - p (edges, rims, apex) is only as good as that difference: the allowance grows as
/// `angle` (the direction's rounding, tol / |sd|) times the size.
void expectSupportingNormal(const Truth& t, const SurfacePoint& s, double tol) {
  const double angle = std::min(1.0, 64 * tol / std::abs(s.signedDistance));
  if (t.convex) {
    EXPECT_NEAR(s.normal.dot(s.point), t.supportValue(s.normal), tol + angle * t.size)
        << "normal does not support the solid at the point";
  } else {
    EXPECT_LT((s.normal - t.tubeNormal(s.point)).norm(), 1e-12 + angle) << "normal is not the tube's";
  }
}

void checkAnswer(const Truth& t, const Vector3d& q) {
  std::ostringstream where;
  where << t.name << " q=(" << q.transpose() << ")";
  SCOPED_TRACE(where.str());
  const SurfacePoint s = t.model->closestPoint(q);
  ASSERT_TRUE(finite(s));
  const double tol = tolerance(t, q);
  EXPECT_NEAR(s.normal.norm(), 1.0, 4 * kEps);
  EXPECT_NEAR(std::abs(s.signedDistance), (q - s.point).norm(), tol);
  const double truth = t.sdf(q);
  EXPECT_NEAR(s.signedDistance, truth, tol);
  if (std::abs(truth) > tol) {
    EXPECT_EQ(s.signedDistance < 0, truth < 0);
    EXPECT_EQ(t.model->inside(q), truth < 0);
  }
  EXPECT_LE(std::abs(t.sdf(s.point)), tolerance(t, s.point)) << "answer is not on the surface";
  if (std::abs(s.signedDistance) > 1e-12 * t.size) {
    const Vector3d expected = (s.signedDistance > 0 ? 1.0 : -1.0) * (q - s.point).normalized();
    EXPECT_LT((s.normal - expected).norm(), 1e-12 + 64 * tol / std::abs(s.signedDistance));
  }
  expectSupportingNormal(t, s, tol);
}

// ---------------------------------------------------------------------------------------------------
// closestPoint, signedDistance, inside.

TEST(Primitives, RandomPointsMatchAnalyticSignedDistance) {
  std::mt19937_64 rng(20240611);
  for (double scale : kScales)
    for (const Truth& t : allShapes(scale)) {
      int in = 0, out = 0;
      for (const Vector3d& q : queryPoints(t, rng, kRandomCases)) {
        checkAnswer(t, q);
        (t.sdf(q) < 0 ? in : out)++;
        if (::testing::Test::HasFailure()) return;  // one clear failure, not thousands
      }
      EXPECT_GT(in, kRandomCases / 4) << t.name;  // both regimes were exercised
      EXPECT_GT(out, kRandomCases * 3 / 4) << t.name;
    }
}

// q = p ± δ·n for a surface point p: whenever the truth says p is at distance δ (nothing nearer), the
// answer is p with normal n — the exact closest point, not merely one at the right distance.
TEST(Primitives, OffsetAlongNormalReturnsTheFootPoint) {
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> unit(0, 1);
  for (double scale : kScales)
    for (const Truth& t : allShapes(scale)) {
      int checked = 0;
      for (int i = 0; i < 3 * kRandomCases / 2; ++i) {
        const SurfaceSample s = sampleSurface(t, rng);
        const double delta = t.size * std::pow(10.0, -9 * unit(rng)) * (unit(rng) < 0.5 ? -0.5 : 0.5);
        const Vector3d q = s.point + delta * s.normal;
        const double tol = tolerance(t, q);
        if (std::abs(std::abs(t.sdf(q)) - std::abs(delta)) > tol) continue;  // something else is nearer
        ++checked;
        const SurfacePoint a = t.model->closestPoint(q);
        ASSERT_LT((a.point - s.point).norm(), 4 * tol) << t.name << " i=" << i;
        ASSERT_NEAR(a.signedDistance, delta, tol) << t.name << " i=" << i;
        // Away from edges the normal is the face's own, to rounding: independent of how small delta is.
        ASSERT_LT((a.normal - s.normal).norm(), 256 * kEps * t.size / t.finest) << t.name << " i=" << i;
      }
      EXPECT_GT(checked, kRandomCases / 2) << t.name;
    }
}

// Points on edges, rims, apexes and axes: on the surface with a defined unit normal.
TEST(Primitives, EdgesAxesAndCorners) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (double scale : kScales)
    for (const Truth& t : allShapes(scale)) {
      std::vector<Vector3d> pts;
      const Vector3d e = t.extent;
      for (int i = 0; i < 300; ++i) {
        const double a = kPi * unit(rng), z = 2 * e.z() * unit(rng);
        pts.push_back(Vector3d(0, 0, z));  // the z axis, inside and beyond
        pts.push_back(Vector3d(0, 0, 1.1 * e.z() * (unit(rng) < 0 ? -1 : 1)));
        pts.push_back(Vector3d(e.x() * std::cos(a), e.x() * std::sin(a), e.z()));  // rim circles
        pts.push_back(Vector3d(e.x() * std::cos(a), e.x() * std::sin(a), -e.z()));
        pts.push_back(Vector3d(e.x() * unit(rng), e.y() * (unit(rng) < 0 ? -1 : 1), e.z()));  // box edges
        pts.push_back(Vector3d(e.x(), e.y() * unit(rng), -e.z()));
        pts.push_back(Vector3d(e.x() * std::cos(a), e.y() * std::sin(a), 0));  // on the x/y extent
      }
      for (int sx = -1; sx <= 1; sx += 2)
        for (int sy = -1; sy <= 1; sy += 2)
          for (int sz = -1; sz <= 1; sz += 2) pts.push_back(e.cwiseProduct(Vector3d(sx, sy, sz)));
      pts.push_back(Vector3d::Zero());
      for (const Vector3d& q : pts) checkAnswer(t, q);
    }
}

// No NaN for any finite query: zeros, subnormals, tiny and huge coordinates in every combination.
TEST(Primitives, ExtremeCoordinatesNeverGiveNaN) {
  const double values[] = {0.0, 5e-324, -5e-324, 1e-300, -1e-300, 1e-160, -1e-160, 1e150, -1e150, 1e300, -1e300};
  for (double scale : kScales)
    for (const Truth& t : allShapes(scale))
      for (double x : values)
        for (double y : values)
          for (double z : values) {
            const Vector3d q(x, y, z);
            const SurfacePoint s = t.model->closestPoint(q);
            ASSERT_TRUE(finite(s)) << t.name << " " << q.transpose();
            ASSERT_NEAR(s.normal.norm(), 1.0, 4 * kEps) << t.name << " " << q.transpose();
            ASSERT_NEAR(std::abs(s.signedDistance), (q - s.point).norm(), tolerance(t, q))
                << t.name << " " << q.transpose();
            ASSERT_LE(std::abs(t.sdf(s.point)), tolerance(t, s.point)) << t.name << " " << q.transpose();
          }
}

// ---------------------------------------------------------------------------------------------------
// The defined answers of primitives.h, exactly.

void expectAnswer(const Model& m, const Vector3d& q, const Vector3d& point, const Vector3d& normal, double sd,
                  double size, int feature) {
  std::ostringstream where;
  where << m.describe() << " q=(" << q.transpose() << ")";
  SCOPED_TRACE(where.str());
  const SurfacePoint s = m.closestPoint(q);
  const double tol = 8 * kEps * size;
  EXPECT_LT((s.point - point).norm(), tol) << s.point.transpose();
  EXPECT_LT((s.normal - normal).norm(), 8 * kEps) << s.normal.transpose();
  EXPECT_NEAR(s.signedDistance, sd, tol);
  EXPECT_EQ(s.feature, feature);
}

TEST(DegeneratePoints, SphereCentreAnswersPlusZ) {
  for (double s : kScales) {
    const double r = 0.7 * s;
    unidist::Sphere sphere(r);
    expectAnswer(sphere, Vector3d::Zero(), Vector3d(0, 0, r), Vector3d::UnitZ(), -r, r, 0);
    expectAnswer(sphere, Vector3d(1e-300, 0, 0), Vector3d(r, 0, 0), Vector3d::UnitX(), -r, r, 0);
  }
}

TEST(DegeneratePoints, BoxTiesGoToTheLowestFace) {
  for (double s : kScales) {
    unidist::Box cube(Vector3d::Constant(s));
    expectAnswer(cube, Vector3d::Zero(), Vector3d(s, 0, 0), Vector3d::UnitX(), -s, s, 0);
    expectAnswer(cube, Vector3d(-0.5 * s, 0, 0), Vector3d(-s, 0, 0), -Vector3d::UnitX(), -0.5 * s, s, 1);
    expectAnswer(cube, Vector3d(0, 0.5 * s, 0.5 * s), Vector3d(0, s, 0.5 * s), Vector3d::UnitY(), -0.5 * s, s, 2);
    // Exactly on an edge and on a corner: the face of lowest id, its normal, distance 0.
    expectAnswer(cube, Vector3d(0.2 * s, -s, -s), Vector3d(0.2 * s, -s, -s), -Vector3d::UnitY(), 0, s, 3);
    expectAnswer(cube, Vector3d(s, s, s), Vector3d(s, s, s), Vector3d::UnitX(), 0, s, 0);
    expectAnswer(cube, Vector3d(-s, -s, -s), Vector3d(-s, -s, -s), -Vector3d::UnitX(), 0, s, 1);
    // Outside: face, edge and vertex regions with their ids.
    expectAnswer(cube, Vector3d(0, 0, -3 * s), Vector3d(0, 0, -s), -Vector3d::UnitZ(), 2 * s, s, 5);
    expectAnswer(cube, Vector3d(0.5 * s, 2 * s, -2 * s), Vector3d(0.5 * s, s, -s), Vector3d(0, 1, -1).normalized(),
                 std::sqrt(2.0) * s, s, 6 + 4 * 0 + 2 * 0 + 1);
    expectAnswer(cube, Vector3d(-2 * s, 2 * s, -2 * s), Vector3d(-s, s, -s), Vector3d(-1, 1, -1).normalized(),
                 std::sqrt(3.0) * s, s, 18 + 4 * 1 + 2 * 0 + 1);
    unidist::Box slab(Vector3d(0.3, 0.6, 1.8) * s);  // thinnest in x: the centre goes to +x
    expectAnswer(slab, Vector3d::Zero(), Vector3d(0.3 * s, 0, 0), Vector3d::UnitX(), -0.3 * s, s, 0);
  }
}

TEST(DegeneratePoints, CapsuleAndCylinderAxisTakePlusX) {
  for (double s : kScales) {
    const double r = 0.4 * s, h = 0.9 * s;
    unidist::Capsule capsule(r, h);
    for (double z : {0.0, 0.5 * h, -h, h})
      expectAnswer(capsule, Vector3d(0, 0, z), Vector3d(r, 0, z), Vector3d::UnitX(), -r, s, 0);
    expectAnswer(capsule, Vector3d(0, 0, h + 2 * r), Vector3d(0, 0, h + r), Vector3d::UnitZ(), r, s, 1);
    expectAnswer(capsule, Vector3d(0, 0, -h - 0.5 * r), Vector3d(0, 0, -h - r), -Vector3d::UnitZ(), -0.5 * r, s, 2);

    const double cr = 0.5 * s, ch = 1.3 * s;
    unidist::Cylinder cylinder(cr, ch);
    expectAnswer(cylinder, Vector3d::Zero(), Vector3d(cr, 0, 0), Vector3d::UnitX(), -cr, s, 0);
    expectAnswer(cylinder, Vector3d(0, 0, ch - 0.1 * s), Vector3d(0, 0, ch), Vector3d::UnitZ(), -0.1 * s, s, 1);
    expectAnswer(cylinder, Vector3d(0, 0, -ch - s), Vector3d(0, 0, -ch), -Vector3d::UnitZ(), s, s, 2);
    // On the rim exactly: the side (first in the tie order) with its normal.
    expectAnswer(cylinder, Vector3d(cr, 0, ch), Vector3d(cr, 0, ch), Vector3d::UnitX(), 0, s, 0);
    expectAnswer(cylinder, Vector3d(0, -cr, -ch), Vector3d(0, -cr, -ch), -Vector3d::UnitY(), 0, s, 0);
    // Outside past the rim: the rim, normal along the way out.
    const Vector3d topRim(cr, 0, ch), bottomRim(0, -cr, -ch), up(0.6, 0, 0.8), down(0, -0.6, -0.8);
    expectAnswer(cylinder, topRim + 5 * s * up, topRim, up, 5 * s, s, 3);
    expectAnswer(cylinder, bottomRim + 5 * s * down, bottomRim, down, 5 * s, s, 4);
    // Exactly as far from side as from top (sizes chosen so that no subtraction rounds): the side.
    unidist::Cylinder even(s, s);
    expectAnswer(even, Vector3d(0.5 * s, 0, 0.5 * s), Vector3d(s, 0, 0.5 * s), Vector3d::UnitX(), -0.5 * s, s, 0);
    expectAnswer(even, Vector3d(0, 0.5 * s, -0.5 * s), Vector3d(0, s, -0.5 * s), Vector3d::UnitY(), -0.5 * s, s, 0);
    expectAnswer(even, Vector3d(0, 0, 0.0), Vector3d(s, 0, 0), Vector3d::UnitX(), -s, s, 0);
  }
}

TEST(DegeneratePoints, ConeApexAxisAndRim) {
  for (double s : kScales) {
    const double r = 0.6 * s, h = 1.1 * s, L = std::hypot(r, 2 * h);
    const Vector3d sideNormalX(2 * h / L, 0, r / L);
    unidist::Cone cone(r, h);
    expectAnswer(cone, Vector3d(0, 0, h), Vector3d(0, 0, h), sideNormalX, 0, s, 0);            // apex itself
    expectAnswer(cone, Vector3d(0, 0, h + s), Vector3d(0, 0, h), Vector3d::UnitZ(), s, s, 3);  // above apex
    expectAnswer(cone, Vector3d(0, 0, -h - s), Vector3d(0, 0, -h), -Vector3d::UnitZ(), s, s, 1);
    expectAnswer(cone, Vector3d(r, 0, -h), Vector3d(r, 0, -h), sideNormalX, 0, s, 0);  // rim itself
    // Inside on the axis: the side toward +x when it is nearer than the base, else the base centre.
    const double z = 0.5 * h, toSide = (h - z) * r / L;
    const Vector3d foot = Vector3d(0, 0, z) + toSide * sideNormalX;
    expectAnswer(cone, Vector3d(0, 0, z), foot, sideNormalX, -toSide, s, 0);
    expectAnswer(cone, Vector3d(0, 0, -h + 0.01 * s), Vector3d(0, 0, -h), -Vector3d::UnitZ(), -0.01 * s, s, 1);
    // Outside beyond the rim along the bisector of the rim's normal cone: the rim.
    const Vector3d out = (sideNormalX + Vector3d(0, 0, -1)).normalized();
    expectAnswer(cone, Vector3d(r, 0, -h) + s * out, Vector3d(r, 0, -h), out, s, s, 2);
    // Apex region off the axis: the apex, normal toward q.
    const Vector3d up = Vector3d(-0.3, 0, 1).normalized();
    expectAnswer(cone, Vector3d(0, 0, h) + s * up, Vector3d(0, 0, h), up, s, s, 3);
  }
}

TEST(DegeneratePoints, TorusAxisAndCentreCircle) {
  for (double s : kScales) {
    const double R = 1.2 * s, r = 0.35 * s;
    unidist::Torus torus(R, r);
    expectAnswer(torus, Vector3d::Zero(), Vector3d(R - r, 0, 0), -Vector3d::UnitX(), R - r, s, 0);
    const double z = 0.7 * s, far = std::hypot(R, z);
    expectAnswer(torus, Vector3d(0, 0, z), Vector3d(R - r * R / far, 0, r * z / far), Vector3d(-R / far, 0, z / far),
                 far - r, s, 0);
    for (const Vector3d& c : {Vector3d(R, 0, 0), Vector3d(0, R, 0), Vector3d(-R, 0, 0), Vector3d(0, -R, 0)})
      expectAnswer(torus, c, c + Vector3d(0, 0, r), Vector3d::UnitZ(), -r, s, 0);
    EXPECT_LT((torus.circlePoint(kPi / 2) - Vector3d(0, R, 0)).norm(), 4 * kEps * R);
  }
}

// ---------------------------------------------------------------------------------------------------
// Brute force: the distance to a dense sampling of the surface agrees with |signedDistance|, inside and out.

TEST(Primitives, DistanceMatchesBruteForceSampling) {
  std::mt19937_64 rng(99);
  for (const Truth& t : allShapes(1.0)) {
    double gap = 0;
    const std::vector<Vector3d> samples = denseSamples(t, gap);
    int outside = 0;
    for (int k = 0; k < kRandomCases / 10; ++k) {
      const Vector3d q = uniformIn(rng, 2.0 * t.extent);
      const SurfacePoint s = t.model->closestPoint(q);
      double brute = std::numeric_limits<double>::infinity();
      for (const Vector3d& p : samples) brute = std::min(brute, (q - p).norm());
      // No sample is nearer than the answer, and the nearest sample is at most gap farther.
      EXPECT_GE(brute, std::abs(s.signedDistance) - 1e-13) << t.name << " k=" << k;
      EXPECT_LE(brute, std::abs(s.signedDistance) + gap) << t.name << " k=" << k;
      outside += s.signedDistance > 0;
    }
    EXPECT_GT(outside, kRandomCases / 40) << t.name;
  }
}

// ---------------------------------------------------------------------------------------------------
// support()

TEST(Primitives, SupportIsExactAndOnTheSurface) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g;
  for (double scale : kScales)
    for (const Truth& t : allShapes(scale)) {
      // Dense surface samples: their best value is a lower bound of the true support value, and at most
      // gap below it.
      double gap = 0;
      const std::vector<Vector3d> samples = denseSamples(t, gap);
      std::vector<Vector3d> dirs = {Vector3d::UnitX(),      -Vector3d::UnitZ(),           Vector3d::UnitZ(),
                                    Vector3d(0, 0, 1e-300), Vector3d(1e-300, -1e-300, 0), Vector3d(3e5, 0, -1e5)};
      for (int i = 0; i < kRandomCases / 10; ++i)
        dirs.push_back(Vector3d(g(rng), g(rng), g(rng)) * std::pow(10.0, 6 * g(rng) / 3));
      for (const Vector3d& dir : dirs) {
        const Vector3d unit = dir.normalized();
        const Vector3d p = t.model->support(dir);
        const double tol = tolerance(t, p);
        ASSERT_TRUE(p.allFinite()) << t.name;
        EXPECT_LE(std::abs(t.sdf(p)), tol) << t.name << " support point off the surface";
        EXPECT_NEAR(unit.dot(p), t.supportValue(unit), tol) << t.name << " dir=" << dir.transpose();
        double brute = -std::numeric_limits<double>::infinity();
        for (const Vector3d& s : samples) brute = std::max(brute, unit.dot(s));
        EXPECT_LE(brute, unit.dot(p) + tol) << t.name;
        EXPECT_GE(brute, unit.dot(p) - gap) << t.name;
      }
      const Vector3d zero = t.model->support(Vector3d::Zero());
      ASSERT_TRUE(zero.allFinite());
      EXPECT_LE(std::abs(t.sdf(zero)), tolerance(t, zero)) << t.name << " support(0) is not a surface point";
    }
}

// ---------------------------------------------------------------------------------------------------
// Surface cells.

/// Every point of the cell's parameter box lies within its radius; its sample is on the surface.
void checkCell(const Truth& t, const SurfaceCell& c, std::mt19937_64& rng) {
  ASSERT_GE(c.face, 0);
  ASSERT_LT(c.face, static_cast<int>(t.faces.size()));
  const FaceDomain& d = t.faces[c.face];
  ASSERT_LE(d.u0, c.u0);
  ASSERT_LE(c.u1, d.u1);
  ASSERT_LE(d.v0, c.v0);
  ASSERT_LE(c.v1, d.v1);
  ASSERT_LT(c.u0, c.u1);
  ASSERT_LT(c.v0, c.v1);
  EXPECT_LE(std::abs(t.sdf(c.sample)), tolerance(t, c.sample)) << t.name << " sample off the surface";
  EXPECT_LE((c.sample - c.center).norm(), c.radius);
  std::uniform_real_distribution<double> unit(0, 1);
  double farthest = 0;
  for (int i = 0; i < 60; ++i) {
    // Corners and edge midpoints first (where the farthest point usually is), then random points.
    const double a = i < 9 ? 0.5 * (i % 3) : unit(rng), b = i < 9 ? 0.5 * (i / 3) : unit(rng);
    const Vector3d p = t.surface(c.face, c.u0 + a * (c.u1 - c.u0), c.v0 + b * (c.v1 - c.v0));
    farthest = std::max(farthest, (p - c.center).norm());
    ASSERT_LE((p - c.center).norm(), c.radius)
        << t.name << " face " << c.face << " cell [" << c.u0 << "," << c.u1 << "]x[" << c.v0 << "," << c.v1 << "]";
  }
  // Rigour comes first, but a radius far beyond the cell's real size would cripple branch-and-bound.
  EXPECT_LE(c.radius, 2.5 * farthest + 64 * kEps * t.size) << t.name;
}

TEST(SurfaceCells, RootsAndSplitsContainTheirSurface) {
  std::mt19937_64 rng(11);
  for (double scale : kScales)
    for (const Truth& t : allShapes(scale)) {
      SCOPED_TRACE(t.name);
      std::vector<SurfaceCell> level = t.model->surfaceCells();
      ASSERT_FALSE(level.empty());
      ASSERT_LE(level.size(), 32u);
      // Together the roots cover every face's whole parameter domain.
      std::uniform_real_distribution<double> unit(0, 1);
      for (int i = 0; i < 2000; ++i) {
        const int f = static_cast<int>(i % t.faces.size());
        const FaceDomain& d = t.faces[f];
        const double u = d.u0 + (d.u1 - d.u0) * unit(rng), v = d.v0 + (d.v1 - d.v0) * unit(rng);
        bool covered = false;
        for (const SurfaceCell& c : level) covered |= c.face == f && c.u0 <= u && u <= c.u1 && c.v0 <= v && v <= c.v1;
        ASSERT_TRUE(covered) << "face " << f << " (" << u << ", " << v << ")";
      }
      double maxRadius = 0;
      for (int depth = 0; depth < 4; ++depth) {
        std::vector<SurfaceCell> next;
        for (const SurfaceCell& c : level) {
          checkCell(t, c, rng);
          if (::testing::Test::HasFatalFailure()) return;
          maxRadius = std::max(maxRadius, c.radius);
          const std::size_t first = next.size();
          t.model->splitCell(c, next);
          ASSERT_EQ(next.size() - first, 4u);
          // The children tile the parent's parameter box.
          double area = 0;
          for (std::size_t k = first; k < next.size(); ++k) {
            EXPECT_EQ(next[k].face, c.face);
            EXPECT_TRUE(next[k].u0 >= c.u0 && next[k].u1 <= c.u1 && next[k].v0 >= c.v0 && next[k].v1 <= c.v1);
            area += (next[k].u1 - next[k].u0) * (next[k].v1 - next[k].v0);
          }
          EXPECT_NEAR(area, (c.u1 - c.u0) * (c.v1 - c.v0), 1e-12 * (c.u1 - c.u0) * (c.v1 - c.v0));
        }
        if (depth < 3) level.swap(next);
      }
      // After three halvings the cells are small.
      double deepest = 0;
      for (const SurfaceCell& c : level) deepest = std::max(deepest, c.radius);
      EXPECT_LT(deepest, 0.2 * maxRadius);
    }
}

// ---------------------------------------------------------------------------------------------------
// Plane

TEST(PlanePrimitive, NormalisesAndAnswersExactly) {
  std::mt19937_64 rng(8);
  std::normal_distribution<double> g;
  for (double scale : kScales)
    for (int k = 0; k < 20; ++k) {
      const Vector3d rawN(g(rng), g(rng), g(rng));
      const double rawD = scale * g(rng) * 3;
      const unidist::Plane plane(rawN * 7.5, rawD * 7.5);
      const Vector3d n = rawN.normalized();
      const double d = rawD / rawN.norm();
      EXPECT_LT((plane.normal() - n).norm(), 4 * kEps);
      EXPECT_NEAR(plane.offset(), d, 8 * kEps * std::abs(d));
      for (int i = 0; i < 500; ++i) {
        const Vector3d q = Vector3d(g(rng), g(rng), g(rng)) * 5 * scale;
        const double truth = n.dot(q) - d;
        const SurfacePoint s = plane.closestPoint(q);
        const double tol = 16 * kEps * (q.norm() + std::abs(d));
        ASSERT_TRUE(finite(s));
        EXPECT_NEAR(s.signedDistance, truth, tol);
        EXPECT_NEAR(n.dot(s.point) - d, 0.0, tol);
        EXPECT_LT((s.normal - n).norm(), 4 * kEps);
        EXPECT_NEAR((q - s.point).norm(), std::abs(truth), tol);
        if (std::abs(truth) > tol) {
          EXPECT_EQ(plane.inside(q), truth < 0);
        }
      }
      // Support: d·n along +n; elsewhere unbounded, answered by a finite far point of the half-space.
      EXPECT_LT((plane.support(2.5 * n) - d * n).norm(), 8 * kEps * (1 + std::abs(d)));
      EXPECT_LT((plane.support(Vector3d::Zero()) - d * n).norm(), 8 * kEps * (1 + std::abs(d)));
      const Vector3d other = plane.support(Vector3d(g(rng), g(rng), g(rng)));
      EXPECT_TRUE(other.allFinite());
      EXPECT_GT(other.norm(), 1e299);
      EXPECT_TRUE(plane.support(-n).allFinite());
      EXPECT_LT(n.dot(plane.support(-n)), -1e299);
    }
}

TEST(PlanePrimitive, TinyAndHugeNormalsAndUnboundedBounds) {
  const unidist::Plane tiny(Vector3d(3e-300, 0, 4e-300), 5e-300);
  EXPECT_LT((tiny.normal() - Vector3d(0.6, 0, 0.8)).norm(), 4 * kEps);
  EXPECT_NEAR(tiny.offset(), 1.0, 4 * kEps);
  const unidist::Plane huge(Vector3d(3e300, 4e300, 0), -5e300);
  EXPECT_LT((huge.normal() - Vector3d(0.6, 0.8, 0)).norm(), 4 * kEps);
  EXPECT_NEAR(huge.offset(), -1.0, 4 * kEps);
  const unidist::Aabb b = huge.localBounds();
  EXPECT_FALSE(b.bounded());
  EXPECT_FALSE(b.empty());
  EXPECT_TRUE(std::isinf(huge.localBoundingSphere().radius));
  EXPECT_TRUE(huge.surfaceCells().empty());
  EXPECT_TRUE(huge.closestPoint(Vector3d::Zero()).param.allFinite());
}

// ---------------------------------------------------------------------------------------------------
// Construction, description, bounds.

template <class Make>
void expectRejected(const Make& make, const std::string& fragment) {
  try {
    make();
    ADD_FAILURE() << "accepted input that should fail with: " << fragment;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(Construction, RejectsBadSizesNamingFieldAndValue) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  try {
    unidist::Sphere(-1);
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "sphere: r must be finite and > 0 (got -1)");
  }
  for (double bad : {0.0, -0.0, -1.0, nan, inf, -inf}) {
    expectRejected([&] { unidist::Sphere s(bad); }, "sphere: r ");
    expectRejected([&] { unidist::Box b(Vector3d(bad, 1, 1)); }, "box: hx ");
    expectRejected([&] { unidist::Box b(Vector3d(1, bad, 1)); }, "box: hy ");
    expectRejected([&] { unidist::Box b(Vector3d(1, 1, bad)); }, "box: hz ");
    expectRejected([&] { unidist::Capsule c(bad, 1); }, "capsule: r ");
    expectRejected([&] { unidist::Capsule c(1, bad); }, "capsule: h ");
    expectRejected([&] { unidist::Cylinder c(bad, 1); }, "cylinder: r ");
    expectRejected([&] { unidist::Cylinder c(1, bad); }, "cylinder: h ");
    expectRejected([&] { unidist::Cone c(bad, 1); }, "cone: r ");
    expectRejected([&] { unidist::Cone c(1, bad); }, "cone: h ");
    expectRejected([&] { unidist::Torus t(bad, 0.5); }, "torus: R ");
    expectRejected([&] { unidist::Torus t(2, bad); }, "torus: r ");
    if (!std::isfinite(bad))
      expectRejected([&] { unidist::Plane p(Vector3d(0, 0, 1), bad); }, "plane: d must be finite");
  }
  expectRejected([&] { unidist::Cone c(1, nan); }, "(got nan)");
  expectRejected([] { unidist::Torus t(1, 1); }, "torus: r must be < R (got R=1, r=1)");
  expectRejected([] { unidist::Torus t(1, 2.5); }, "torus: r must be < R");
  expectRejected([] { unidist::Plane p(Vector3d::Zero(), 1); }, "plane: normal");
  expectRejected([&] { unidist::Plane p(Vector3d(nan, 0, 1), 1); }, "plane: normal");
  expectRejected([&] { unidist::Plane p(Vector3d(inf, 0, 1), 1); }, "plane: normal");
  expectRejected([] { unidist::Plane p(Vector3d(1e-300, 0, 0), 1e300); }, "plane: d");
}

TEST(Construction, DescribeBoundsAndFlags) {
  EXPECT_EQ(unidist::Sphere(0.5).describe(), "sphere r=0.5");
  EXPECT_EQ(unidist::Box(Vector3d(1, 2, 0.25)).describe(), "box hx=1 hy=2 hz=0.25");
  EXPECT_EQ(unidist::Capsule(0.1, 2).describe(), "capsule r=0.10000000000000001 h=2");
  EXPECT_EQ(unidist::Torus(2, 0.5).describe(), "torus R=2 r=0.5");
  EXPECT_EQ(unidist::Plane(Vector3d(0, 0, 2), 3).describe(), "plane nx=0 ny=0 nz=1 d=1.5");
  EXPECT_EQ(std::string(unidist::toString(unidist::Cone(1, 1).type())), "cone");
  EXPECT_FALSE(unidist::Torus(2, 1).isConvex());
  EXPECT_TRUE(unidist::Cylinder(2, 1).isConvex());
  EXPECT_GE(unidist::Box(Vector3d(1, 2, 3)).memoryBytes(), sizeof(unidist::Box));

  std::mt19937_64 rng(4);
  for (double scale : kScales)
    for (const Truth& t : allShapes(scale)) {
      const unidist::Aabb b = t.model->localBounds();
      EXPECT_LT((b.max - t.extent).norm(), 4 * kEps * t.size) << t.name;
      EXPECT_LT((b.min + t.extent).norm(), 4 * kEps * t.size) << t.name;
      const unidist::BoundingSphere bs = t.model->localBoundingSphere();
      for (int i = 0; i < 500; ++i) {
        const Vector3d p = sampleSurface(t, rng).point;
        EXPECT_LE(b.distanceTo(p), 4 * kEps * t.size) << t.name;
        EXPECT_LE((p - bs.center).norm(), bs.radius) << t.name;
      }
    }
}

// ---------------------------------------------------------------------------------------------------
// Aabb helpers of model.cpp.

TEST(AabbMath, TransformedHoldsEveryMovedCornerAndNoMore) {
  std::mt19937_64 rng(21);
  std::normal_distribution<double> g;
  for (int k = 0; k < 200; ++k) {
    unidist::Aabb box;
    box.extend(Vector3d(g(rng), g(rng), g(rng)));
    box.extend(Vector3d(g(rng), g(rng), g(rng)));
    const Eigen::Isometry3d X =
        Eigen::Translation3d(g(rng), g(rng), g(rng)) * Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized();
    const unidist::Aabb moved = box.transformed(X);
    unidist::Aabb corners;
    for (int c = 0; c < 8; ++c)
      corners.extend(X * Vector3d(c & 1 ? box.max.x() : box.min.x(), c & 2 ? box.max.y() : box.min.y(),
                                  c & 4 ? box.max.z() : box.min.z()));
    EXPECT_TRUE((moved.min.array() <= corners.min.array()).all());
    EXPECT_TRUE((moved.max.array() >= corners.max.array()).all());
    EXPECT_LT((moved.min - corners.min).norm() + (moved.max - corners.max).norm(), 1e-13);
  }
  // A half-space's box stays NaN-free; an empty box stays empty.
  unidist::Aabb half;
  half.min = Vector3d(-1, -1, -std::numeric_limits<double>::infinity());
  half.max = Vector3d(1, 1, 0);
  const unidist::Aabb turned = half.transformed(Eigen::Isometry3d(Eigen::AngleAxisd(kPi / 2, Vector3d::UnitX())));
  EXPECT_FALSE(turned.min.hasNaN() || turned.max.hasNaN());
  EXPECT_TRUE(unidist::Aabb().transformed(Eigen::Isometry3d::Identity()).empty());
  const unidist::Aabb shifted = half.transformed(Eigen::Isometry3d(Eigen::Translation3d(0, 0, 5)));
  EXPECT_NEAR(shifted.max.z(), 5, 64 * kEps);
  EXPECT_GE(shifted.max.z(), 5);
  EXPECT_EQ(shifted.min.z(), -std::numeric_limits<double>::infinity());
}

TEST(AabbMath, DistanceTo) {
  unidist::Aabb b;
  b.min = Vector3d(-1, -2, -3);
  b.max = Vector3d(1, 2, 3);
  EXPECT_EQ(b.distanceTo(Vector3d(0.5, 0, 0)), 0);
  EXPECT_DOUBLE_EQ(b.distanceTo(Vector3d(4, 6, 3)), 5);
  EXPECT_DOUBLE_EQ(b.distanceTo(Vector3d(0, 0, -1e300)), 1e300);
  EXPECT_TRUE(std::isinf(unidist::Aabb().distanceTo(Vector3d::Zero())));
}

}  // namespace
