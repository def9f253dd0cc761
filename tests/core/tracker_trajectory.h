// Recorded trajectories for the tracker's tests and benchmark: a ball moved smoothly over a torus (major radius
// kR, tube kTube) into and out of contact, deterministic for a seed.
#pragma once

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace tracker_trajectory {

using Iso = Eigen::Isometry3d;
using Vec = Eigen::Vector3d;

constexpr double kR = 1.0, kTube = 0.25, kBall = 0.3;  // torus major / tube radius, ball radius

/// A smooth pseudo-random path of the ball's centre around the torus: angle φ along the ring (crossing the
/// seam at 0), angle θ around the tube, and a gap oscillating from an overlap of `deepest` to `highest` apart;
/// the ball turns about a slowly changing axis. Each coordinate is a sum of three sinusoids of random phase.
struct Trajectory {
  double sweep = 2 * M_PI;  ///< time covered: the path's length scales with it (steps fix its resolution)
  int steps = 300;
  double deepest = 0.03, highest = 0.12;
  unsigned seed = 1;

  std::vector<Iso> poses() const {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> phase(0, 2 * M_PI), freq(0.6, 1.4);
    auto smooth = [&]() {  // three (phase, frequency) pairs
      std::array<std::array<double, 2>, 3> w{};
      for (std::size_t k = 0; k < 3; ++k) w[k] = {phase(rng), freq(rng) * static_cast<double>(k + 1)};
      return [w](double t) {
        double s = 0;
        for (std::size_t k = 0; k < 3; ++k) s += std::sin(w[k][1] * t + w[k][0]) / static_cast<double>(k + 1);
        return s / 1.84;  // about [-1, 1]
      };
    };
    const auto fPhi = smooth(), fTheta = smooth(), fGap = smooth(), fAx = smooth(), fAy = smooth();
    std::vector<Iso> out;
    for (int i = 0; i < steps; ++i) {
      const double t = sweep * i / steps;
      const double phi = 0.9 * fPhi(t), theta = 0.8 * fTheta(t);
      const double gap = 0.5 * (highest - deepest) * (1 + fGap(t)) - deepest;
      const double rho = kTube + kBall + gap;
      Iso X = Iso::Identity();
      X.translation() = Vec((kR + rho * std::cos(theta)) * std::cos(phi), (kR + rho * std::cos(theta)) * std::sin(phi),
                            rho * std::sin(theta));
      X.linear() = Eigen::AngleAxisd(1.5 * t, Vec(fAx(t), fAy(t), 1).normalized()).toRotationMatrix();
      out.push_back(X);
    }
    return out;
  }
};

}  // namespace tracker_trajectory
