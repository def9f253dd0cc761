// Penetration depth of convex NURBS solids (exact rational ellipsoids, proved convex: GJK/EPA on their support
// maps) beside FCL's analytic ellipsoids (GJK/EPA by libccd and by FCL's own solver) on the same poses, against
// the truth (the minimum of the analytic support functions, ellipsoid_truth.h). Per depth band: median time,
// worst error, our status. Random poses of two ellipsoids (semi-axes 1 × 0.6 × 0.35 and 0.8 × 0.8 × 0.3).
// usage: unidist_bench_nurbs_convex_depth [poses per band]   (default 40)
#include "bench/ellipsoid_truth.h"
#include "bench/median.h"

#include "unidist/distance.h"
#include "unidist/nurbs.h"

#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>
#include <vector>

namespace {

using Vec = Eigen::Vector3d;
using Clock = std::chrono::steady_clock;

double microsSince(Clock::time_point t0) { return std::chrono::duration<double, std::micro>(Clock::now() - t0).count(); }

struct Case {
  Eigen::Isometry3d pose;
  double truth;
};

/// FCL's deepest contact between the two ellipsoids (0 when it finds none).
double fclDepth(const Vec& axesA, const Vec& axesB, const Eigen::Isometry3d& X, fcl::GJKSolverType solver) {
  fcl::CollisionObjectd a(std::make_shared<fcl::Ellipsoidd>(axesA)), b(std::make_shared<fcl::Ellipsoidd>(axesB));
  b.setTransform(fcl::Transform3d(X.matrix()));
  a.computeAABB();
  b.computeAABB();
  fcl::CollisionRequestd request(1, true);
  request.gjk_solver_type = solver;
  fcl::CollisionResultd result;
  fcl::collide(&a, &b, request, result);
  double depth = 0;
  for (std::size_t k = 0; k < result.numContacts(); ++k) depth = std::max(depth, result.getContact(k).penetration_depth);
  return depth;
}

/// FCL's signed distance (libccd's GJK/EPA): minus the depth when overlapping.
double fclSignedDepth(const Vec& axesA, const Vec& axesB, const Eigen::Isometry3d& X) {
  fcl::CollisionObjectd a(std::make_shared<fcl::Ellipsoidd>(axesA)), b(std::make_shared<fcl::Ellipsoidd>(axesB));
  b.setTransform(fcl::Transform3d(X.matrix()));
  fcl::DistanceRequestd request;
  request.enable_signed_distance = true;
  request.gjk_solver_type = fcl::GST_LIBCCD;  // FCL's own solver has no ellipsoid distance (it asserts)
  fcl::DistanceResultd result;
  fcl::distance(&a, &b, request, result);
  return -result.min_distance;
}

template <class F>
double timedMedian(int reps, F&& f) {
  std::vector<double> t;
  for (int k = 0; k < reps; ++k) {
    const auto t0 = Clock::now();
    f();
    t.push_back(microsSince(t0));
  }
  return median(t);
}

}  // namespace

int main(int argc, char** argv) {
  const int perBand = argc > 1 ? std::atoi(argv[1]) : 40;
  const ellipsoid_truth::Ellipsoid a{Vec(1.0, 0.6, 0.35), Eigen::Isometry3d::Identity()};
  const Vec axesB(0.8, 0.8, 0.3);
  const unidist::NurbsModel ma({ellipsoid_truth::surface(a.axes)}, true), mb({ellipsoid_truth::surface(axesB)}, true);
  std::printf("proved convex: A %d, B %d\n", ma.provedConvex(), mb.provedConvex());
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  struct Band {
    const char* name;
    double lo, hi;  // depth, relative to the size (A's box diagonal, 2.42)
  };
  const double size = ma.localBounds().diagonal();
  const Band bands[] = {{"shallow (< 1% of size)", 0, 0.01}, {"medium (1-10%)", 0.01, 0.1}, {"deep (> 10%)", 0.1, 10}};
  std::printf("# csv,band,poses,unidist_us,unidist_worst_error,unidist_1e-6_us,unidist_1e-6_worst_error,certified,fcl_ccd_us,fcl_ccd_worst_error,fcl_indep_us,"
              "fcl_indep_worst_error,fcl_signed_us,fcl_signed_worst_error\n");
  for (const Band& band : bands) {
    std::vector<Case> cases;
    for (int tries = 0; static_cast<int>(cases.size()) < perBand && tries < 200000; ++tries) {
      Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
      X.linear() = Eigen::Quaterniond(Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
      X.translation() = 1.2 * Vec(u(rng), u(rng), u(rng));
      const double truth = ellipsoid_truth::depth(a, {axesB, X});
      if (truth > band.lo * size && truth <= band.hi * size) cases.push_back({X, truth});
    }
    std::vector<double> ours, coarse, ccd, indep, signedFcl;
    double worstOurs = 0, worstCoarse = 0, worstCcd = 0, worstIndep = 0, worstSigned = 0;
    int certified = 0;
    unidist::DistanceOptions options;
    options.tolerance = 1e-9 * size;
    for (const Case& c : cases) {
      unidist::DistanceResult r;
      ours.push_back(timedMedian(5, [&] { r = unidist::distance(ma, Eigen::Isometry3d::Identity(), mb, c.pose, options); }));
      worstOurs = std::max(worstOurs, std::abs(-r.distance - c.truth));
      certified += r.status == unidist::Status::Certified;
      unidist::DistanceOptions asFcl;  // FCL's default distance tolerance, 1e-6
      asFcl.tolerance = 1e-6;
      coarse.push_back(timedMedian(5, [&] { r = unidist::distance(ma, Eigen::Isometry3d::Identity(), mb, c.pose, asFcl); }));
      worstCoarse = std::max(worstCoarse, std::abs(-r.distance - c.truth));
      certified += r.status == unidist::Status::Certified;
      double d = 0;
      ccd.push_back(timedMedian(5, [&] { d = fclDepth(a.axes, axesB, c.pose, fcl::GST_LIBCCD); }));
      worstCcd = std::max(worstCcd, std::abs(d - c.truth));
      indep.push_back(timedMedian(5, [&] { d = fclDepth(a.axes, axesB, c.pose, fcl::GST_INDEP); }));
      worstIndep = std::max(worstIndep, std::abs(d - c.truth));
      signedFcl.push_back(timedMedian(5, [&] { d = fclSignedDepth(a.axes, axesB, c.pose); }));
      worstSigned = std::max(worstSigned, std::abs(d - c.truth));
    }
    std::printf("%-24s %3zu poses | unidist %8.1f us, worst error %.1e; at 1e-6 %8.1f us, worst error %.1e; certified %d of %zu | FCL libccd %7.1f us, worst "
                "error %.1e | FCL indep %7.1f us, worst error %.1e | FCL signed distance %7.1f us, worst error %.1e\n",
                band.name, cases.size(), median(ours), worstOurs, median(coarse), worstCoarse, certified, 2 * cases.size(), median(ccd), worstCcd,
                median(indep), worstIndep, median(signedFcl), worstSigned);
    std::printf("csv,%s,%zu,%.4g,%.3g,%.4g,%.3g,%d,%.4g,%.3g,%.4g,%.3g,%.4g,%.3g\n", band.name, cases.size(), median(ours), worstOurs,
                median(coarse), worstCoarse, certified, median(ccd), worstCcd, median(indep), worstIndep, median(signedFcl), worstSigned);
  }
  return 0;
}
