// The ten pair families of the extremes suite (primitive, mesh, cloud, NURBS, each against each), as a gtest
// parameter: every extreme is one test run once per family pair.
#pragma once

#include "core/case_budget.h"
#include "core/extremes_models.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace extremes {

using unidist::testing::sci;

struct FamilyPair {
  Family a, b;  // a <= b in the order prim, mesh, cloud, nurbs
};

inline std::vector<FamilyPair> allFamilyPairs() {
  const Family all[] = {Family::Prim, Family::Mesh, Family::Cloud, Family::Nurbs};
  std::vector<FamilyPair> out;
  for (int i = 0; i < 4; ++i)
    for (int j = i; j < 4; ++j) out.push_back({all[i], all[j]});
  return out;
}

inline std::string familyPairName(const ::testing::TestParamInfo<FamilyPair>& info) {
  return std::string(familyName(info.param.a)) + "_" + familyName(info.param.b);
}

class FamilyPairTest : public ::testing::TestWithParam<FamilyPair> {};

}  // namespace extremes
