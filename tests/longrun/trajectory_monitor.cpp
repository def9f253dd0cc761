#include "trajectory_monitor.h"

#include "unidist/mass.h"
#include "unidist/primitives.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

namespace longrun {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

bool finite(const unidist::BodyState& s) {
  return s.pose.matrix().allFinite() && s.linearVelocity.allFinite() && s.angularVelocity.allFinite();
}

/// FNV-1a over the bytes of the doubles: equal fingerprints mean (all but certainly) bitwise-equal states.
void mix(std::uint64_t& h, const double* values, std::size_t n) {
  unsigned char bytes[sizeof(double)];
  for (std::size_t i = 0; i < n; ++i) {
    std::memcpy(bytes, &values[i], sizeof(double));
    for (unsigned char b : bytes) h = (h ^ b) * 1099511628211ull;
  }
}

std::uint64_t fingerprint(const std::vector<unidist::BodyState>& bodies) {
  std::uint64_t h = 1469598103934665603ull;
  for (const unidist::BodyState& s : bodies) {
    mix(h, s.pose.matrix().data(), 16);
    mix(h, s.linearVelocity.data(), 3);
    mix(h, s.angularVelocity.data(), 3);
  }
  return h;
}

double diagonal(const unidist::Model& m) { return m.localBounds().diagonal(); }

}  // namespace

TrajectoryMonitor::TrajectoryMonitor(const unidist::Scene& scene, const Bounds& bounds, int steps)
    : scene_(scene), bounds_(bounds) {
  const double g = scene.gravity.norm();
  up_ = g > 0 ? Eigen::Vector3d(-scene.gravity / g) : Eigen::Vector3d::UnitZ();
  const std::size_t n = scene.bodies.size();
  minGroundClearance.assign(n, kInf);
  maxDriftAfterSettling.assign(n, 0);
  settledPlaces_.assign(n, Eigen::Vector3d::Zero());
  groundAllowance.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const unidist::SceneBody& b = scene.bodies[i];
    if (b.isStatic) {
      if (const auto* plane = dynamic_cast<const unidist::Plane*>(b.model.get())) {
        const Eigen::Vector3d nW = b.pose.linear() * plane->normal();
        grounds_.emplace_back(nW, plane->offset() + nW.dot(b.pose.translation()));
      }
      continue;
    }
    const unidist::PrincipalInertia p = unidist::principalInertia(unidist::massProperties(*b.model), b.mass);
    dynamic_.push_back({i, b.mass, p.X_MB, p.moments});
    groundAllowance[i] = bounds.groundAllowance * diagonal(*b.model);
    energyBound += bounds.energyAllowance * b.mass * g * diagonal(*b.model);
  }
  // Stacked pairs, from the initial poses: footprints (world boxes across `up`) overlap and the upper body's
  // origin is above the lower body's top.
  for (const DynamicBody& lo : dynamic_)
    for (const DynamicBody& hi : dynamic_) {
      if (lo.index == hi.index) continue;
      const unidist::SceneBody& a = scene.bodies[lo.index];
      const unidist::SceneBody& b = scene.bodies[hi.index];
      const unidist::Aabb boxA = a.model->localBounds().transformed(a.pose);
      const unidist::Aabb boxB = b.model->localBounds().transformed(b.pose);
      bool overlap = true;
      for (int k = 0; k < 3; ++k)
        if (std::abs(up_[k]) < 0.5) overlap = overlap && boxA.min[k] < boxB.max[k] && boxB.min[k] < boxA.max[k];
      const double topA = std::max(up_.dot(boxA.min), up_.dot(boxA.max));
      if (overlap && up_.dot(b.pose.translation()) > topA) stacked_.push_back({lo.index, hi.index});
    }
  minStackGap = kInf;
  // Allocated and written now: pages first touched during the run would count as growth of the resident set.
  fingerprints_.assign(static_cast<std::size_t>(steps) + 1, ~std::uint64_t{0});
}

double TrajectoryMonitor::energy(const std::vector<unidist::BodyState>& bodies) const {
  double e = 0;
  for (const DynamicBody& d : dynamic_) {
    const unidist::BodyState& s = bodies[d.index];
    const Eigen::Isometry3d X_WB = s.pose * d.X_MB;
    const Eigen::Vector3d wB = X_WB.linear().transpose() * s.angularVelocity;
    e += 0.5 * d.mass * s.linearVelocity.squaredNorm() + 0.5 * wB.dot(d.moments.cwiseProduct(wB)) -
         d.mass * scene_.gravity.dot(X_WB.translation());
  }
  return e;
}

double TrajectoryMonitor::lowest(std::size_t i, const Eigen::Isometry3d& X_WM, const Eigen::Vector3d& up) const {
  const Eigen::Vector3d p = X_WM * scene_.bodies[i].model->support(X_WM.linear().transpose() * -up);
  return up.dot(p);
}

void TrajectoryMonitor::observe(int step, const std::vector<unidist::BodyState>& bodies) {
  fingerprints_.at(static_cast<std::size_t>(step)) = fingerprint(bodies);
  for (const unidist::BodyState& s : bodies)
    if (!finite(s)) {
      if (firstNonFiniteStep < 0) firstNonFiniteStep = step;
      return;  // nothing below means anything for this step
    }
  for (const DynamicBody& d : dynamic_)
    for (const auto& [n, offset] : grounds_) {
      const double clearance = lowest(d.index, bodies[d.index].pose, n) - offset;
      minGroundClearance[d.index] = std::min(minGroundClearance[d.index], clearance);
    }
  for (const StackedPair& p : stacked_) {
    const double gap = lowest(p.upper, bodies[p.upper].pose, up_) - lowest(p.lower, bodies[p.lower].pose, up_);
    const bool ordered = up_.dot(bodies[p.upper].pose.translation()) > up_.dot(bodies[p.lower].pose.translation());
    minStackGap = std::min(minStackGap, gap);
    if ((gap <= 0 || !ordered) && stackViolationStep < 0) stackViolationStep = step;
  }
  if (step == bounds_.settleStep)
    for (std::size_t i = 0; i < bodies.size(); ++i) settledPlaces_[i] = bodies[i].pose.translation();
  if (step >= bounds_.settleStep)
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const Eigen::Vector3d move = bodies[i].pose.translation() - settledPlaces_[i];
      maxDriftAfterSettling[i] = std::max(maxDriftAfterSettling[i], (move - up_.dot(move) * up_).norm());
    }
  const double e = energy(bodies);
  if (step == 0) initialEnergy = e;
  if (step == bounds_.settleStep) settledEnergy = e;
  maxExcessOverInitial = std::max(maxExcessOverInitial, e - initialEnergy);
  if (step >= bounds_.settleStep) maxExcessAfterSettling = std::max(maxExcessAfterSettling, e - settledEnergy);
  const bool gained =
      e - initialEnergy > energyBound || (step >= bounds_.settleStep && e - settledEnergy > energyBound);
  if (gained && energyViolationStep < 0) energyViolationStep = step;
}

std::vector<std::string> TrajectoryMonitor::violations() const {
  std::vector<std::string> out;
  auto say = [&out](const auto&... parts) {
    std::ostringstream s;
    (s << ... << parts);
    out.push_back(s.str());
  };
  if (firstNonFiniteStep >= 0) say("non-finite state at step ", firstNonFiniteStep);
  for (std::size_t i = 0; i < minGroundClearance.size(); ++i)
    if (minGroundClearance[i] < -groundAllowance[i])
      say(scene_.bodies[i].name, " sank ", -minGroundClearance[i], " into the ground (allowance ", groundAllowance[i],
          ")");
  if (stackViolationStep >= 0) say("a stacked pair lost its order at step ", stackViolationStep);
  if (energyViolationStep >= 0)
    say("energy gain beyond ", energyBound, " at step ", energyViolationStep, " (max over E(0): ", maxExcessOverInitial,
        ", max over E(settled): ", maxExcessAfterSettling, ")");
  return out;
}

}  // namespace longrun
