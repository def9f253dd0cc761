// What single-precision engine data costs: Bullet on Debian is built with btScalar = float, so poses and shapes
// reach the plugin rounded to float (the plugin renormalises the float quaternion in double, eigen_bullet.h).
// The same separated pairs as the suite, exact in double (gap 0.1 by the support-plane construction), are asked
// again with every pose and every model coordinate rounded through float; the change of the answer is measured
// against what the rounding predicts — half a float ulp per translation coordinate (0.0625 at 1e6), a rotation
// off by about 2^-23 rad (times the lever arm, the model's size) and model data off by 2^-24 of its coordinates.
#include "core/extremes_families.h"

#include <cstdio>
#include <cstdlib>

namespace extremes {
namespace {

constexpr double kFloatEps = 1.0 / (1 << 23);  // float's epsilon, 2^-23

double floatUlp(double x) {
  const float f = static_cast<float>(std::abs(x));
  return static_cast<double>(std::nextafter(f, 2 * f + 1) - f);
}

/// A pose as a single-precision engine holds it, read back as the plugin reads it.
Pose throughFloat(const Pose& X) {
  const Eigen::Quaternionf qf(Eigen::Quaterniond(X.linear()).cast<float>());
  Pose Y = Pose::Identity();
  Y.linear() = Eigen::Quaterniond(qf.cast<double>()).normalized().toRotationMatrix();
  Y.translation() = X.translation().cast<float>().cast<double>();
  return Y;
}

Vec roundedToFloat(const Vec& v) { return v.cast<float>().cast<double>(); }

/// The same model with its data rounded to float (sizes, vertices, control points).
Body throughFloat(const Body& b) {
  switch (b.family) {
    case Family::Prim:
      return b.kind == Kind::Ball ? ball(Family::Prim, static_cast<float>(b.radius)) : box(Family::Prim, roundedToFloat(b.half));
    case Family::Mesh: {
      Body m = b;
      meshfix::Soup soup = b.soup;
      for (Vec& v : soup.vertices) v = roundedToFloat(v);
      setMesh(m, std::move(soup));
      return m;
    }
    case Family::Cloud: {
      Body c = b;
      std::vector<Vec> points = b.points;
      for (Vec& p : points) p = roundedToFloat(p);
      setCloud(c, std::move(points));
      return c;
    }
    case Family::Nurbs:  // a float NURBS sphere: its radius in float (the control points are multiples of it)
      return ball(Family::Nurbs, static_cast<float>(b.radius));
  }
  return b;
}

struct Worst {
  double error = 0, predicted = 0;
};

TEST(FloatEngineData, ErrorStaysWithinTheFloatRoundingOfPosesAndModels) {
  std::mt19937_64 rng(51);
  const bool print = std::getenv("UNIDIST_EXTREMES_TABLE") != nullptr;
  for (Family f : {Family::Prim, Family::Mesh, Family::Cloud, Family::Nurbs})
    for (const auto& [offset, scale] : {std::pair{0.0, 1e-3}, {0.0, 1.0}, {0.0, 1e3}, {1e3, 1.0}, {1e6, 1.0}}) {
      Worst worst;
      for (int k = 0; k < 6; ++k) {
        const Body a = box(f == Family::Nurbs ? Family::Prim : f, scale * Vec(0.5, 0.4, 0.3)), b = ball(f, 0.35 * scale);
        Pose XA = randomRotation(rng), XB = randomRotation(rng);
        XA.translation() = offset * randomUnit(rng) + scale * randomUnit(rng);
        const double gap = 0.1 * scale;
        placeAtGap(a, XA, b, XB, randomUnit(rng), gap);
        const Pose XAf = throughFloat(XA), XBf = throughFloat(XB);
        const Body af = throughFloat(a), bf = throughFloat(b);
        const unidist::DistanceResult r = unidist::distance(*af.model, XAf, *bf.model, XBf);
        // Predicted: translations (half an ulp per coordinate, both poses), rotations (2^-23 rad times the lever
        // arm, the model's extent from its origin), model data (2^-24 of its coordinates), and the tolerance.
        const double reach = 0.71 * scale;
        const double predicted = std::sqrt(3.0) * 0.5 * (floatUlp(XA.translation().cwiseAbs().maxCoeff()) +
                                                        floatUlp(XB.translation().cwiseAbs().maxCoeff())) +
                                 2 * kFloatEps * reach + 2 * 0.5 * kFloatEps * reach +
                                 unidist::defaultTolerance(*af.model, XAf, *bf.model, XBf);
        const double error = std::abs(r.distance - gap);
        EXPECT_LE(error, predicted) << familyName(f) << " offset " << offset << " scale " << scale;
        worst.error = std::max(worst.error, error);
        worst.predicted = std::max(worst.predicted, predicted);
      }
      if (print)
        std::printf("FLOAT %s-%s | offset %.0e | scale %.0e | float ulp of the offset %.2e | worst error %.2e | "
                    "predicted bound %.2e\n",
                    familyName(f == Family::Nurbs ? Family::Prim : f), familyName(f), offset, scale,
                    offset > 0 ? floatUlp(offset) : 0.0, worst.error, worst.predicted);
    }
}

}  // namespace
}  // namespace extremes
