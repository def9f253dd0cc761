// NurbsSurface::restricted: the part of a surface over a parameter range (how CAD files restrict a surface), the
// same points and derivatives at the same parameters, its domain the range; bad ranges rejected by name.
#include "core/nurbs_fixtures.h"
#include "unidist/nurbs.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace {

using Vec = Eigen::Vector3d;
using unidist::NurbsSurface;

/// Every point and first derivative of `part` on a grid over its domain against `whole` at the same parameters.
void expectSameSurface(const NurbsSurface& whole, const NurbsSurface& part, double size) {
  for (int i = 0; i <= 12; ++i)
    for (int j = 0; j <= 12; ++j) {
      const double u = part.uMin() + (part.uMax() - part.uMin()) * i / 12.0;
      const double v = part.vMin() + (part.vMax() - part.vMin()) * j / 12.0;
      const unidist::SurfaceDerivatives a = whole.derivatives(u, v), b = part.derivatives(u, v);
      ASSERT_LT((a.point - b.point).norm(), 1e-13 * size) << u << " " << v;
      ASSERT_LT((a.du - b.du).norm(), 1e-11 * (1 + a.du.norm()) * size) << u << " " << v;
      ASSERT_LT((a.dv - b.dv).norm(), 1e-11 * (1 + a.dv.norm()) * size) << u << " " << v;
    }
}

/// A bicubic surface on uniform, unclamped knot vectors (domain [3, 5] x [3, 4]), random control points.
NurbsSurface unclampedSurface() {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(-1, 1), W(0.5, 2);
  std::vector<std::vector<Eigen::Vector4d>> net(5, std::vector<Eigen::Vector4d>(4));
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 4; ++j) net[i][j] = Eigen::Vector4d(i + 0.3 * U(rng), j + 0.3 * U(rng), U(rng), W(rng));
  return NurbsSurface(3, 3, {0, 1, 2, 3, 4, 5, 6, 7, 8}, {0, 1, 2, 3, 4, 5, 6, 7}, net);
}

TEST(NurbsRestrict, SamePointsOverTheRange) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(0, 1);
  for (const NurbsSurface& s : {nurbs_fixtures::sphereSurface(), nurbs_fixtures::torusSurface(),
                                nurbs_fixtures::wavySurface(), unclampedSurface()})
    for (int k = 0; k < 20; ++k) {
      // Random sub-ranges, some starting or ending on a knot or on the domain's ends.
      double u[2] = {U(rng), U(rng)}, v[2] = {U(rng), U(rng)};
      if (k % 4 == 1) u[0] = 0, v[1] = 1;
      if (k % 4 == 2) u[0] = 0.25, v[0] = 0.5;
      std::sort(u, u + 2);
      std::sort(v, v + 2);
      if (!(u[1] > u[0] + 1e-3 && v[1] > v[0] + 1e-3)) continue;
      const auto at = [](double lo, double hi, double x) { return lo + (hi - lo) * x; };
      const double u0 = at(s.uMin(), s.uMax(), u[0]), u1 = at(s.uMin(), s.uMax(), u[1]);
      const double v0 = at(s.vMin(), s.vMax(), v[0]), v1 = at(s.vMin(), s.vMax(), v[1]);
      const NurbsSurface part = s.restricted(u0, u1, v0, v1);
      EXPECT_EQ(part.uMin(), u0);
      EXPECT_EQ(part.uMax(), u1);
      EXPECT_EQ(part.vMin(), v0);
      EXPECT_EQ(part.vMax(), v1);
      expectSameSurface(s, part, 4);
    }
}

TEST(NurbsRestrict, WholeDomainIsTheSameSurface) {
  for (const NurbsSurface& s : {nurbs_fixtures::torusSurface(), unclampedSurface()}) {
    const NurbsSurface same = s.restricted(s.uMin(), s.uMax(), s.vMin(), s.vMax());
    expectSameSurface(s, same, 4);
  }
}

// A band of the sphere about its equator is an open model every point of which is 1 from the centre; the
// points of the sphere outside the band are farther from a point beyond it.
TEST(NurbsRestrict, SphereBandAsAModel) {
  const NurbsSurface sphere = nurbs_fixtures::sphereSurface();
  const NurbsSurface band = sphere.restricted(sphere.uMin(), sphere.uMax(), 0.4, 0.6);
  const unidist::NurbsModel model({band}, false);
  EXPECT_NEAR(model.closestPoint(Vec::Zero()).signedDistance, 1, 1e-12);
  const Vec top = band.evaluate(0.3, 0.6);  // on the band's upper rim
  const Vec q = 3 * Vec::UnitZ() * (top.z() > 0 ? 1 : -1);
  double nearest = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= 400; ++i) nearest = std::min(nearest, (band.evaluate(i / 400.0, top.z() > 0 ? 0.6 : 0.4) - q).norm());
  EXPECT_NEAR(model.closestPoint(q).signedDistance, nearest, 1e-9);
}

TEST(NurbsRestrict, BadRangesAreRejected) {
  const NurbsSurface s = nurbs_fixtures::torusSurface();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto message = [&](double u0, double u1, double v0, double v1) {
    try {
      (void)s.restricted(u0, u1, v0, v1);
    } catch (const unidist::InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message(0.5, 0.5, 0, 1).find("u range"), std::string::npos);  // empty
  EXPECT_NE(message(0.6, 0.4, 0, 1).find("u range"), std::string::npos);  // reversed
  EXPECT_NE(message(0, 1, -0.1, 1).find("v range"), std::string::npos);   // outside the domain
  EXPECT_NE(message(0, 1, 0, 1.5).find("knot domain"), std::string::npos);
  EXPECT_NE(message(nan, 1, 0, 1).find("u range"), std::string::npos);
  EXPECT_NE(message(0, 1, 0, std::numeric_limits<double>::infinity()).find("v range"), std::string::npos);
}

}  // namespace
