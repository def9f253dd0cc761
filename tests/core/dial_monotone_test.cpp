// The tolerance dial on every pair family (tests/core/dial_families.h: fixed poses, exact truths), tolerance
// from 1e-1 to 1e-12 of the model size:
//  * DialContract: the bounds always hold the truth and a certified answer is within its tolerance (the
//    contract, docs/query-contract.md);
//  * DialMonotone: the true error never grows beyond the looser tolerance's (up to rounding) — not promised by
//    the contract, but what a user turning the dial expects.
// Two suites so that a breach of the contract and a non-monotone dial fail under different names. The benchmark
// of the same cases is tests/bench/dial_bench.cpp (docs/dial.md).
#include "core/dial_families.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace dial {
void PrintTo(const FamilyBuilder& b, std::ostream* os) { *os << b.name; }  // gtest names the family on failure
}  // namespace dial

namespace {

/// Rounding allowance: the truths and our answers are both a few ulps of the coordinates off.
double rounding(const dial::Case& c) { return 1e-13 * c.size; }

struct Answer {
  double relative;  // requested tolerance / size
  unidist::DistanceResult result;
  std::string where;  // for failure messages
};

const dial::Library& library() {
  static const dial::Library instance;
  return instance;
}

/// Poses per kind of pair: four where queries and truths are cheap, fewer where a family's sweep costs seconds
/// (each suite recomputes it: ctest runs every test in its own process).
int posesPerKind(const std::string& family) {
  for (const char* cheap : {"prim-prim", "prim-mesh", "prim-cloud", "cloud-cloud"})
    if (family == cheap) return 4;
  return family == "mesh-cloud" ? 1 : 2;  // mesh-cloud: the winding-number truth of 1,000 points per case
}

/// Every case of the family at the twelve tolerances, loosest first (computed once per process).
const std::vector<std::pair<dial::Case, std::vector<Answer>>>& sweep(const dial::FamilyBuilder& builder) {
  static std::map<std::string, std::vector<std::pair<dial::Case, std::vector<Answer>>>> done;
  auto it = done.find(builder.name);
  if (it != done.end()) return it->second;
  auto& out = done[builder.name];
  for (const dial::Case& c : builder.build(library(), posesPerKind(builder.name)).cases) {
    std::vector<Answer> answers;
    for (int k = 1; k <= 12; ++k) {
      const double relative = std::pow(10.0, -k);
      unidist::DistanceOptions options;
      options.tolerance = relative * c.size;
      const unidist::DistanceResult r = unidist::distance(*c.a->model, c.Xa, *c.b->model, c.Xb, options);
      char where[200];
      std::snprintf(where, sizeof where, "%s at tolerance %.0e x size (%s, %s), truth %.17g, distance %.17g",
                    c.what.c_str(), relative, r.method, unidist::toString(r.status), c.truth, r.distance);
      answers.push_back({relative, r, where});
    }
    out.emplace_back(c, std::move(answers));
  }
  return out;
}

class DialContract : public testing::TestWithParam<dial::FamilyBuilder> {};
class DialMonotone : public testing::TestWithParam<dial::FamilyBuilder> {};

TEST_P(DialContract, BoundsHoldAndCertifiedWithinTolerance) {
  int penetrating = 0;
  for (const auto& [c, answers] : sweep(GetParam())) {
    penetrating += c.penetrating;
    for (const Answer& a : answers) {
      SCOPED_TRACE(a.where);
      EXPECT_LE(a.result.lowerBound, c.truth + rounding(c));
      EXPECT_GE(a.result.upperBound, c.truth - rounding(c));
      if (a.result.status == unidist::Status::Certified) {
        EXPECT_LE(std::abs(a.result.distance - c.truth), a.relative * c.size + rounding(c));
      }
    }
  }
  RecordProperty("penetrating_cases", penetrating);
}

/// A penetration depth by the translation search is resolved to its final bisection step, a quarter of the
/// tolerance, and its escape direction to the polish's stop (core/src/generic/translation_depth.cpp): within
/// that step it lands wherever the search's path puts it, so a looser answer may be closer by luck. Separation
/// answers are polished to rounding and get no such allowance.
double depthStep(const dial::Case& c, const Answer& a) {
  return std::string(a.result.method) == "translation-depth-bnb" ? 0.25 * a.relative * c.size : 0.0;
}

// Every family, NURBS ones included: their separation answers end with a local polish of the winning pair
// (core/src/generic/pair_polish.h), so where the search stopped no longer shows in the error.
TEST_P(DialMonotone, ErrorNeverGrowsAsToleranceTightens) {
  for (const auto& [c, answers] : sweep(GetParam())) {
    double looserError = std::numeric_limits<double>::infinity();
    for (const Answer& a : answers) {
      SCOPED_TRACE(a.where);
      const double error = std::abs(a.result.distance - c.truth);
      EXPECT_LE(error, std::max(looserError, rounding(c) + depthStep(c, a))) << "the true error grew as the tolerance tightened";
      looserError = error;
    }
  }
}

std::string familyName(const testing::TestParamInfo<dial::FamilyBuilder>& info) {
  std::string name = info.param.name;
  for (char& ch : name) ch = ch == '-' ? '_' : ch;
  return name;
}

INSTANTIATE_TEST_SUITE_P(Families, DialContract, testing::ValuesIn(dial::familyBuilders()), familyName);
INSTANTIATE_TEST_SUITE_P(Families, DialMonotone, testing::ValuesIn(dial::familyBuilders()), familyName);

}  // namespace
