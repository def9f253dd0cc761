// Small helpers the query tests share: a pure translation, and whether a model's lazily built structure exists.
#pragma once

#include "unidist/model.h"

#include <gtest/gtest.h>

#include <string>

namespace query_test {

inline Eigen::Isometry3d translation(const Eigen::Vector3d& t) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = t;
  return X;
}

/// Model::structures()'s entry `name` is built; a model without such a structure fails the test.
inline bool structureBuilt(const unidist::Model& m, const std::string& name) {
  for (const unidist::StructureReport& s : m.structures())
    if (s.name == name) return s.built;
  ADD_FAILURE() << "no structure " << name;
  return false;
}

}  // namespace query_test
