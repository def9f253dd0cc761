// The subdivided bound of a rational Bézier function's maximum (core/src/nurbs/ratio_subdivision.h) against
// dense sampling, and on the form it exists for: one that does not change along one direction.
#include "nurbs/bspline.h"
#include "nurbs/ratio_subdivision.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace unidist::nurbs {
namespace {

struct Form {
  int p, q;
  std::vector<double> a, w;
  double at(double s, double t) const {
    std::array<std::array<double, kMaxNurbsDegree + 1>, 3> bs, bt;
    bernstein(p, s, bs);
    bernstein(q, t, bt);
    double num = 0, den = 0;
    for (int i = 0; i <= p; ++i)
      for (int j = 0; j <= q; ++j) {
        const double b = bs[0][static_cast<std::size_t>(i)] * bt[0][static_cast<std::size_t>(j)];
        num += b * a[static_cast<std::size_t>(i * (q + 1) + j)];
        den += b * w[static_cast<std::size_t>(i * (q + 1) + j)];
      }
    return num / den;
  }
  double sampledMax(int n) const {
    double best = -std::numeric_limits<double>::infinity();
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j) best = std::max(best, at(double(i) / n, double(j) / n));
    return best;
  }
};

// −(v − 1/3)² times a weight varying along u only: the ratios are equal along u, the maximum 0 lies on the
// line v = 1/3 (in Bernstein form, degree 2: −1/9, 2/9, −4/9, whose largest coefficient bounds it by 2/9).
Form valleyAlongU() {
  const std::array<double, 3> wu{1.0, 0.7, 1.0}, f{-1.0 / 9, 2.0 / 9, -4.0 / 9};
  Form form{2, 2, {}, {}};
  for (double weight : wu)
    for (double value : f) {
      form.a.push_back(weight * value);
      form.w.push_back(weight);
    }
  return form;
}

TEST(RatioSubdivision, SplitsAcrossTheDirectionThatCurvesOnly) {
  const Form form = valleyAlongU();
  // Halving along u would leave every piece's bound at 2/9: the budget is enough only when each split is across v.
  const RatioBound r = subdividedRatioBound(form.p, form.q, form.a.data(), form.w.data(), {1e-12, 0.0, 64});
  EXPECT_LE(r.upper, 1e-12);
  EXPECT_GE(r.upper, 0.0);  // never below the true maximum
  EXPECT_LE(r.reached, 0.0);
  EXPECT_GT(r.splits, 10);
  EXPECT_LT(r.splits, 64);
}

TEST(RatioSubdivision, StopsAtACornerAboveEnough) {
  const Form form = valleyAlongU();
  // The value at v = 0 is −1/9: asking for −0.2 can never succeed, and the corners say so at once.
  const RatioBound r = subdividedRatioBound(form.p, form.q, form.a.data(), form.w.data(), {-0.2, 0.0, 64});
  EXPECT_EQ(r.splits, 0);
  EXPECT_NEAR(r.upper, 2.0 / 9, 1e-15);
}

TEST(RatioSubdivision, BoundsRandomFormsFromAbove) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> value(-1, 1), weight(0.5, 2);
  std::uniform_int_distribution<int> degree(1, 4);
  int refined = 0;
  for (int k = 0; k < 300; ++k) {
    Form form{degree(rng), degree(rng), {}, {}};
    const bool flatAlongU = k % 2 == 0;  // every other form equal along u: the ones subdivision is for
    std::vector<double> column(static_cast<std::size_t>(form.q + 1));
    for (double& c : column) c = value(rng);
    for (int i = 0; i <= form.p; ++i)
      for (int j = 0; j <= form.q; ++j) {
        const double w = weight(rng);
        form.a.push_back(w * (flatAlongU ? column[static_cast<std::size_t>(j)] : value(rng)));
        form.w.push_back(w);
      }
    // Asked for a bound just above the maximum (from a fine grid; a grid's miss of a maximum is second order in
    // its spacing, ~1e-5 here).
    const double sampled = form.sampledMax(400);
    const RatioBound r =
        subdividedRatioBound(form.p, form.q, form.a.data(), form.w.data(), {sampled + 1e-4, 1e-15, 200});
    SCOPED_TRACE(k);
    EXPECT_GE(r.upper, sampled);
    EXPECT_LE(r.reached, r.upper);
    // Split only where one direction does not curve (equal along u, or of degree 1), and then to the bound asked.
    if (r.splits > 0) {
      refined += flatAlongU ? 1 : 0;
      EXPECT_TRUE(flatAlongU || form.p == 1 || form.q == 1);
      EXPECT_LE(r.upper, sampled + 1e-4);
    }
  }
  EXPECT_GT(refined, 30);  // the others were settled by their coefficients or a corner
}

}  // namespace
}  // namespace unidist::nurbs
