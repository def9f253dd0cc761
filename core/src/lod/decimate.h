// A point cloud's level of detail: one point per cell of a voxel grid (docs/dial.md, "Level of detail"). Internal.
#pragma once

#include "lod/stand_in_cache.h"
#include "unidist/point_cloud.h"

namespace unidist::lod {

/// Keeps the first point (in input order, with its normal) of every cell of a grid of side maxDeviation/√3, so
/// every dropped point lies within maxDeviation of a kept one; the deviation reported is the largest such
/// distance actually met (the Hausdorff distance is at most that: the kept points are points of the cloud).
/// Null model when no point would be dropped.
Built decimate(const PointCloud& cloud, double maxDeviation);

}  // namespace unidist::lod
