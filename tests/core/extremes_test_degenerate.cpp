// Degenerate input in every family, separated (gap 1e-3, exact by the support-plane construction) and
// overlapping by 0.1 along the same construction (truth from signedDistanceOracle):
//  * primitives: a plate 1e-7 thick, a needle capsule of radius 1e-6;
//  * meshes: a box whose faces are fans of needle triangles 1e-9 of the edge wide, with zero-area (repeated index,
//    exactly collinear) and duplicated triangles in the input;
//  * clouds: every point given three times, one point fifty times;
//  * NURBS: a sphere whose circle has an inner knot of full multiplicity (degree + 1) and a repeated control
//    point, and a sphere whose rational weights span 1e-6 ... 1e6 (the same exact sphere, reparametrised).
// Every degenerate model of one family meets every degenerate model of the other.
#include "core/extremes_families.h"

namespace extremes {
namespace {

// Weights spanning 1e-6 ... 1e6 (NurbsWeightsSpanning1e_6To1e6, below, tells what they broke before).
constexpr double kWorkingWeightSpan = 1e6;

std::vector<Body> degenerateBodies(Family f) {
  switch (f) {
    case Family::Prim: return {thinBox(0.4, 5e-8), needleCapsule(1e-6, 0.4)};
    case Family::Mesh: return {needleBox(Vec(0.4, 0.3, 0.25))};
    case Family::Cloud: return {duplicatePointBall(0.35)};
    case Family::Nurbs: return {fullMultiplicityBall(0.35), extremeWeightBall(0.35, kWorkingWeightSpan)};
  }
  return {};
}

class Degenerate : public FamilyPairTest {};

TEST(DegenerateModels, AreWhatTheyClaim) {
  // The needle box keeps every needle, drops the three bad triangles and stays a convex solid box.
  const Body box = needleBox(Vec(0.4, 0.3, 0.25));
  const auto& mesh = static_cast<const unidist::TriangleMesh&>(*box.model);
  EXPECT_TRUE(mesh.isSolid());
  EXPECT_TRUE(mesh.isConvex());
  EXPECT_EQ(mesh.stats().droppedZeroArea, 2u);
  EXPECT_EQ(mesh.stats().droppedDuplicate, 1u);
  EXPECT_EQ(mesh.triangles().size(), 6u * 8u);
  // Both reparametrised NURBS spheres are the exact sphere: points of every patch lie on it.
  for (const Body& b : {fullMultiplicityBall(0.35), extremeWeightBall(0.35, kWorkingWeightSpan)}) {
    const auto& nurbs = static_cast<const unidist::NurbsModel&>(*b.model);
    EXPECT_TRUE(nurbs.isSolid());
    for (const unidist::RationalBezierPatch& patch : nurbs.patches())
      for (double s : {0.0, 0.3, 1.0})
        for (double t : {0.0, 0.7, 1.0}) EXPECT_NEAR(patch.evaluate(s, t).norm(), 0.35, 1e-15) << b.label;
  }
}

TEST_P(Degenerate, SeparatedAndOverlapping) {
  const FamilyPair p = GetParam();
  std::mt19937_64 rng(31);
  for (const Body& a : degenerateBodies(p.a))
    for (const Body& b : degenerateBodies(p.b))
      for (double gap : {1e-3, -0.1}) {
        const Pose XA = randomRotation(rng);
        Pose XB = randomRotation(rng);
        placeAtGap(a, XA, b, XB, randomUnit(rng), gap);
        const std::optional<double> truth = gap > 0 ? std::optional<double>(gap) : signedDistanceOracle(a, XA, b, XB);
        if (!truth) continue;  // a plate against a needle: no independent depth (both are exact primitives)
        Case c = makeCase("degenerate", a, XA, b, XB, exactly(*truth));
        c.what += gap > 0 ? " apart 1e-3" : " overlapping";
        runCase(c);
      }
}

// Rational weights with a large ratio along a patch make the parametrisation extremely uneven (a quarter circle
// with end weights 1e6 and 1e-6 runs almost all of its length within 1e-6 of one parameter end). The NURBS point
// query subdivides at parameter midpoints: before the patches' weights were balanced by a Möbius
// reparametrisation (core/src/nurbs/reparametrise.h) it spent its whole budget and returned a point that was
// not the closest, with no sign of it — on this sphere of radius 0.35, 30 random points: end weights 1/W..W gave
// 0.1 ms and exact answers for W <= 10, 37 ms for 1e3, 270 ms and errors up to 3.2e-2 for 1e6.
TEST(DegenerateModels, NurbsWeightsSpanning1e_6To1e6) {
  const Body sphere = extremeWeightBall(0.35, 1e6);
  std::mt19937_64 rng(32);
  for (int k = 0; k < 10; ++k) {
    const Vec q = 0.6 * randomUnit(rng);
    const unidist::SurfacePoint s = sphere.model->closestPoint(q);
    EXPECT_NEAR(s.signedDistance, 0.6 - 0.35, 1e-12);
    // The reported NURBS parameters are the original surface's (the Möbius map undone); evaluating that
    // parametrisation is ill-conditioned here (|dS/du| up to ~1e6 × r), hence 1e-9, not rounding.
    const auto& nurbs = static_cast<const unidist::NurbsModel&>(*sphere.model);
    EXPECT_LT((nurbs.surfaces()[static_cast<std::size_t>(s.feature)].evaluate(s.param.x(), s.param.y()) - s.point).norm(),
              1e-9);
  }
  const Body plate = thinBox(0.4, 5e-8);
  const Pose XA = randomRotation(rng);
  Pose XB = randomRotation(rng);
  placeAtGap(plate, XA, sphere, XB, randomUnit(rng), 1e-3);
  runCase(makeCase("degenerate", plate, XA, sphere, XB, exactly(1e-3)));
}

INSTANTIATE_TEST_SUITE_P(Extremes, Degenerate, ::testing::ValuesIn(allFamilyPairs()), familyPairName);

}  // namespace
}  // namespace extremes
