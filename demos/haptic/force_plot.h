// Force-vs-time line plots of a haptic replay as PNG: |F| and its x, y, z components against time, with axes,
// ticks, a title and a legend (plot_canvas.h draws them).
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

namespace unidist::haptic {

/// One plot of `force[i]` at time i · timeStep. Throws InputError naming the file when it cannot be written.
void writeForcePlot(const std::string& path, const std::string& title, const std::vector<Eigen::Vector3d>& force,
                    double timeStep);

}  // namespace unidist::haptic
