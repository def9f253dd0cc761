// Helpers of the mesh benchmark against FCL (tests/bench/mesh_vs_fcl.cpp): FCL models from our meshes, FCL
// queries, medians of repeated timings, generated tori.
#pragma once

#include "unidist/mesh.h"

#include <fcl/fcl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <ctime>
#include <memory>
#include <vector>

namespace bench {

/// The calling thread's CPU time: on the shared 2-core machine wall time also counts the time the query waited
/// for a core (runs minutes apart differed by 2× under load), CPU time does not; both sides of every comparison
/// run single-threaded on the same clock, and on an idle machine the two clocks agree.
struct ThreadCpuClock {
  using duration = std::chrono::nanoseconds;
  using rep = duration::rep;
  using period = duration::period;
  using time_point = std::chrono::time_point<ThreadCpuClock>;
  static constexpr bool is_steady = true;
  static time_point now() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return time_point(duration(static_cast<rep>(ts.tv_sec) * 1000000000 + ts.tv_nsec));
  }
};
using Clock = ThreadCpuClock;

template <class BV>
std::shared_ptr<fcl::BVHModel<BV>> fclMesh(const unidist::TriangleMesh& m) {
  auto g = std::make_shared<fcl::BVHModel<BV>>();
  std::vector<fcl::Vector3d> v(m.vertices().begin(), m.vertices().end());
  std::vector<fcl::Triangle> t;
  for (const auto& tri : m.triangles()) t.emplace_back(tri[0], tri[1], tri[2]);
  g->beginModel();
  g->addSubModel(v, t);
  g->endModel();
  return g;
}

inline fcl::Transform3d fclPose(const Eigen::Isometry3d& X) {
  fcl::Transform3d T = fcl::Transform3d::Identity();
  T.linear() = X.linear();
  T.translation() = X.translation();
  return T;
}

/// FCL's distance between two geometries with nearest points (what our answers carry too).
inline double fclDistance(const fcl::CollisionGeometryd* a, const Eigen::Isometry3d& Xa,
                          const fcl::CollisionGeometryd* b, const Eigen::Isometry3d& Xb) {
  fcl::DistanceRequestd request;
  request.enable_nearest_points = true;
  fcl::DistanceResultd result;
  fcl::distance(a, fclPose(Xa), b, fclPose(Xb), request, result);
  return result.min_distance;
}

/// Calls per timed sample for a call that took `firstMicros`: enough for ~200 µs (see medianMicros), at most `most`.
inline int batchFor(double firstMicros, int most) {
  return std::clamp(static_cast<int>(200.0 / std::max(firstMicros, 1e-3)), 1, most);
}

/// Median of one call's CPU time in µs. Reading the thread's CPU clock costs ~1.6 µs here (a system call, where
/// the wall clock costs 0.03), so calls are timed in batches of at least ~200 µs and each sample is a batch's
/// time over its calls; the samples adapt to the call's cost (5 to maxReps, ~0.5 s).
template <class F>
double medianMicros(int maxReps, F&& f) {
  const auto t0 = Clock::now();
  f();
  const double first = std::max(std::chrono::duration<double, std::micro>(Clock::now() - t0).count(), 1e-3);
  const int batch = batchFor(first, 1000);
  const int reps = std::clamp(static_cast<int>(5e5 / (first * batch)), 5, maxReps);
  std::vector<double> times;
  for (int i = 0; i < reps; ++i) {
    const auto t1 = Clock::now();
    for (int k = 0; k < batch; ++k) f();
    times.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t1).count() / batch);
  }
  std::nth_element(times.begin(), times.begin() + reps / 2, times.end());
  return times[static_cast<std::size_t>(reps / 2)];
}

/// Torus about z (major radius R, minor r) tessellated into 2·n·m triangles, outward oriented.
inline std::unique_ptr<unidist::TriangleMesh> torus(double R, double r, int n, int m) {
  std::vector<Eigen::Vector3d> v;
  std::vector<unidist::TriangleMesh::Triangle> t;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double u = 2 * M_PI * i / n, w = 2 * M_PI * j / m;
      v.emplace_back((R + r * std::cos(w)) * std::cos(u), (R + r * std::cos(w)) * std::sin(u), r * std::sin(w));
    }
  const auto id = [&](int i, int j) { return static_cast<std::uint32_t>(((i % n) * m) + (j % m)); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      t.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      t.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return std::make_unique<unidist::TriangleMesh>(std::move(v), std::move(t));
}

}  // namespace bench
