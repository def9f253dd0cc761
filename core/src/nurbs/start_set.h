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
  std::vector<Sample> samples;          // the grid (2^depth + 1)² per patch
  std::vector<Eigen::Vector3d> points;  // the surface point of each sample (a node corner)
  // The same, coordinate by coordinate, for loops the compiler vectorises: the samples' points, and the
  // nodes' ball centres and radii.
  std::vector<double> px, py, pz, cx, cy, cz, radius;
};

/// The forest's start set, made on first call.
const StartSet& startSet(const PatchForest& forest);

}  // namespace unidist::nurbs
