// NURBS – point cloud beside the generic routine, same inputs, same run (docs/nurbs.md, "Pair routines").
//
//   unidist_bench_nurbs_cloud MODELS_DIR [repeats=11]
//
// MODELS_DIR holds torus_nurbs.unurbs.json, torus_cloud.xyz and sphere_cloud.xyz (the shared acceptance models).
// Per pose: the median time of distance() (the dispatcher's routine) and of genericDistance(), alternating:
// warm (after one untimed query: the NURBS patch-tree nodes it met are cached) and cold (each query on a freshly
// loaded NURBS model, as one `unidist distance` command runs; the cloud's tree is built before the timing, as the
// command does); their answers, bounds and status. The touching pose moves the sphere cloud of the 3-apart pose along the answer's normal by
// the distance, so its closest point lands on the torus. Answers that disagree beyond the two widths fail the run.
#include "bench/median.h"
#include "unidist/adapters/load.h"
#include "unidist/distance.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

using unidist::DistanceResult;

struct Timed {
  DistanceResult result;
  double us;
};

template <class Query>
Timed timeOnce(Query&& query) {
  const auto t0 = std::chrono::steady_clock::now();
  DistanceResult r = query();
  const auto t1 = std::chrono::steady_clock::now();
  return {r, std::chrono::duration<double, std::micro>(t1 - t0).count()};
}

void print(const char* who, const DistanceResult& r, double warmUs, double coldUs) {
  std::printf("  %-8s %-32s warm %9.1f us  cold %9.1f us  distance %.15g  [%.15g, %.15g] %s\n", who, r.method,
              warmUs, coldUs, r.distance, r.lowerBound, r.upperBound, unidist::toString(r.status));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s MODELS_DIR [repeats]\n", argv[0]);
    return 2;
  }
  const std::string dir = argv[1];
  const int repeats = argc > 2 ? std::max(1, std::atoi(argv[2])) : 11;
  const auto torus = unidist::loadModel(dir + "/torus_nurbs.unurbs.json");
  const auto torusCloud = unidist::loadModel(dir + "/torus_cloud.xyz");
  const auto sphereCloud = unidist::loadModel(dir + "/sphere_cloud.xyz");
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  auto at = [](double x, double y, double z) { return Eigen::Isometry3d(Eigen::Translation3d(x, y, z)); };

  // The touching pose: the 3-apart sphere cloud moved by the distance against its answer's normal.
  const DistanceResult apart = unidist::distance(*torus, I, *sphereCloud, at(3, 0, 0));
  const Eigen::Isometry3d touching = at(3, 0, 0).pretranslate(-apart.distance * apart.normal);

  struct Case {
    const char* name;
    const unidist::Model& cloud;
    Eigen::Isometry3d pose;
  };
  const std::vector<Case> cases = {{"torus_cloud at (2.7, 0, 0)", *torusCloud, at(2.7, 0, 0)},
                                   {"sphere_cloud at (3, 0, 0)", *sphereCloud, at(3, 0, 0)},
                                   {"torus_cloud at (0.3, 0, 0.2)", *torusCloud, at(0.3, 0, 0.2)},
                                   {"sphere_cloud touching", *sphereCloud, touching}};
  std::printf("NURBS torus (torus_nurbs.unurbs.json) against 10,000-point clouds; %d repeats, medians\n", repeats);
  int failures = 0;
  for (const Case& c : cases) {
    auto ours = [&] { return unidist::distance(*torus, I, c.cloud, c.pose); };
    auto generic = [&] { return unidist::genericDistance(*torus, I, c.cloud, c.pose); };
    ours();
    generic();
    std::vector<double> tOurs, tGeneric, coldOurs, coldGeneric;
    DistanceResult rOurs, rGeneric;
    for (int k = 0; k < repeats; ++k) {
      const Timed a = timeOnce(ours), b = timeOnce(generic);
      tOurs.push_back(a.us);
      tGeneric.push_back(b.us);
      rOurs = a.result;
      rGeneric = b.result;
      const auto fresh = unidist::loadModel(dir + "/torus_nurbs.unurbs.json");
      coldOurs.push_back(timeOnce([&] { return unidist::distance(*fresh, I, c.cloud, c.pose); }).us);
      const auto fresh2 = unidist::loadModel(dir + "/torus_nurbs.unurbs.json");
      coldGeneric.push_back(timeOnce([&] { return unidist::genericDistance(*fresh2, I, c.cloud, c.pose); }).us);
    }
    const double mOurs = median(tOurs), mGeneric = median(tGeneric);
    std::printf("%s\n", c.name);
    print("ours", rOurs, mOurs, median(coldOurs));
    print("generic", rGeneric, mGeneric, median(coldGeneric));
    std::printf("  generic / ours: warm %.1fx, cold %.1fx\n", mGeneric / mOurs, median(coldGeneric) / median(coldOurs));
    const bool agree = rOurs.lowerBound <= rGeneric.upperBound && rGeneric.lowerBound <= rOurs.upperBound;
    if (!agree) {
      std::printf("  DISAGREE: the two brackets do not meet\n");
      ++failures;
    }
  }
  return failures == 0 ? 0 : 1;
}
