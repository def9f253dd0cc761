// Where the patch search starts: every patch's tree cut at one depth, and the surface points on the grid of
// that cut's node corners. The shallow nodes have loose balls and wide cones, so a query near the surface used
// to pop and split nearly all of them one by one before any was pruned; starting from the cut bounds each
// start node once. The grid gives the first upper bound and the Newton seed (the nearest grid point is
// nearly always in the global minimum's basin, unlike the nearest control point). Only speed depends on it:
// the cut covers every patch, and every patch corner is a grid point. Built once per forest, on first use
// (std::call_once: queries may run concurrently). Internal.
#pragma once

#include "nurbs/patch_tree.h"

#include <vector>

namespace unidist::nurbs {

/// At most this many start nodes: the cut is as deep as that allows (and no deeper than the cached tree).
constexpr std::size_t kMaxStartNodes = 64;

struct StartSet {
  int depth = 0;
  std::vector<const PatchNode*> nodes;  // the cut, patch by patch
  struct Sample {
    int patch;
    double s, t;  // local parameters of the patch
  };
  std::vector<Sample> samples;  // the grid (2^depth + 1)² per patch
  // Coordinate by coordinate, for loops the compiler vectorises: each sample's surface point (a node corner),
  // and the nodes' ball centres and radii.
  std::vector<double> px, py, pz, cx, cy, cz, radius;
  Eigen::Vector3d point(std::size_t k) const { return {px[k], py[k], pz[k]}; }
  /// The memory its arrays take.
  std::size_t bytes() const {
    std::size_t doubles = 0;
    for (const std::vector<double>* v : {&px, &py, &pz, &cx, &cy, &cz, &radius}) doubles += v->capacity();
    return sizeof(StartSet) + samples.capacity() * sizeof(Sample) + nodes.capacity() * sizeof(const PatchNode*) +
           doubles * sizeof(double);
  }
};

/// The forest's start set, made on first call.
const StartSet& startSet(const PatchForest& forest);

}  // namespace unidist::nurbs
