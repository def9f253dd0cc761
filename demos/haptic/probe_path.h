// A probe's path through its waypoints, sampled at the servo steps: Catmull-Rom on positions (through every
// waypoint, velocity continuous) and slerp on rotations with a smoothstep in time, so the rotation's speed is
// continuous too (it eases to zero at each waypoint) and the tracker never sees a jump.
#pragma once

#include <Eigen/Geometry>

#include <vector>

namespace unidist::haptic {

/// `steps` (>= 2) poses from the first waypoint to the last, each of the (waypoints − 1) segments taking an
/// equal share of the steps.
std::vector<Eigen::Isometry3d> samplePath(const std::vector<Eigen::Isometry3d>& waypoints, int steps);

}  // namespace unidist::haptic
