// Separated and touching pairs of every family at extreme scales, far from the origin, at gaps from 1e-12 to
// 1e3 of the size, touching, and with near-parallel faces. Truth is exact by construction: B's lowest point
// along n is placed gap·n above A's highest (extremes_models.h, placeAtGap), so the slab between the two
// support planes proves the distance is the gap.
#include "core/extremes_families.h"

namespace extremes {
namespace {

const Vec kBoxHalf(0.5, 0.4, 0.3);
constexpr double kBallRadius = 0.35;

/// A box of A's family against a ball of B's family, random rotations, B placed at `gap` along a random n.
Case separated(const FamilyPair& p, const std::string& extreme, double scale, const Vec& offset, double gap,
               std::mt19937_64& rng) {
  const Body a = box(p.a, scale * kBoxHalf), b = ball(p.b, scale * kBallRadius);
  Pose XA = randomRotation(rng), XB = randomRotation(rng);
  XA.translation() = offset + scale * randomUnit(rng);
  placeAtGap(a, XA, b, XB, randomUnit(rng), gap);
  return makeCase(extreme, a, XA, b, XB, exactly(gap));
}

class Separation : public FamilyPairTest {};

TEST_P(Separation, ScalesFrom1e6To1e_6) {
  std::mt19937_64 rng(11);
  for (double scale : {1e-6, 1e-3, 1.0, 1e3, 1e6}) runCase(separated(GetParam(), "scale " + sci(scale), scale, Vec::Zero(), 0.1 * scale, rng));
}

TEST_P(Separation, UnitModelsAMillionFromTheOrigin) {
  std::mt19937_64 rng(12);
  const Vec far(1e6, -7e5, 3e5);
  for (double gap : {0.1, 1e-4}) runCase(separated(GetParam(), "offset 1e6", 1.0, far, gap, rng));
}

TEST_P(Separation, GapsFrom1e_12To1e3) {
  std::mt19937_64 rng(13);
  for (double gap : {1e-12, 1e-9, 1e-6, 1e-3, 1.0, 1e3}) {
    Case c = separated(GetParam(), "gap " + sci(gap), 1.0, Vec::Zero(), gap, rng);
    // A gap below the default tolerance (1e-9 × size) asks for a tenth of itself: the answer must see it.
    if (gap < 1e-8) c.options.tolerance = gap / 10;
    runCase(c);
  }
}

TEST_P(Separation, ExactlyTouching) {
  std::mt19937_64 rng(14);
  for (int k = 0; k < 2; ++k) {
    Case c = separated(GetParam(), "touching", 1.0, Vec::Zero(), 0.0, rng);
    c.options.tolerance = 1e-12;
    runCase(c);
  }
}

/// Box against box, B's faces turned by theta from A's: the nearest features are a face and an almost parallel
/// face, the worst case for directions computed from differences of points.
TEST_P(Separation, NearParallelFacesFrom1e_9To1e_3Rad) {
  const FamilyPair p = GetParam();
  std::mt19937_64 rng(15);
  for (double theta : {1e-9, 1e-6, 1e-3})
    for (double gap : {1e-3, 1e-9}) {
      const Body a = box(p.a, kBoxHalf), b = box(p.b, Vec(0.45, 0.35, 0.25));
      const Pose R = randomRotation(rng);
      Pose XA = R, XB = R * rotation(Vec(1, 0.3, 0), theta);
      placeAtGap(a, XA, b, XB, R.linear() * Vec::UnitZ(), gap);
      Case c = makeCase("near-parallel", a, XA, b, XB, exactly(gap));
      c.what += " theta " + sci(theta) + " gap " + sci(gap);
      if (gap < 1e-8) c.options.tolerance = gap / 10;
      runCase(c);
    }
}

/// A flat sheet (a biquadratic rational NURBS patch, a flat mesh, a grid of points, a plate) over a box face, turned by
/// 1e-6 rad. Pairs with an open NURBS surface go through the generic search, whose branch and bound sees every
/// cell of a near-parallel face at nearly the same bound: one case, as it is the slowest in the suite.
TEST_P(Separation, NearParallelSheet) {
  const FamilyPair p = GetParam();
  std::mt19937_64 rng(16);
  // A primitive plane is a half-space (nothing to tilt over a face): its sheet is a plate 1e-7 thick.
  const Body a = box(p.a, kBoxHalf), b = p.b == Family::Prim ? thinBox(0.3, 5e-8) : sheet(p.b, 0.3);
  const Pose R = randomRotation(rng);
  Pose XA = R, XB = R * rotation(Vec(1, 0.3, 0), 1e-6);
  placeAtGap(a, XA, b, XB, R.linear() * Vec::UnitZ(), 1e-3);
  Case c = makeCase("near-parallel", a, XA, b, XB, exactly(1e-3));
  c.what += " theta 1e-6 gap 1e-3";
  runCase(c);
}

INSTANTIATE_TEST_SUITE_P(Extremes, Separation, ::testing::ValuesIn(allFamilyPairs()), familyPairName);

}  // namespace
}  // namespace extremes
