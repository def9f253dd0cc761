// Mesh–cloud and cloud–cloud group of the mesh benchmark (no FCL counterpart): ours against brute force.
#include "mesh_vs_fcl_util.h"
#include "unidist/adapters/load.h"
#include "unidist/distance.h"
#include "unidist/point_cloud.h"

#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

void cloudGroup(const std::string& models, const unidist::TriangleMesh& t20) {
  const auto cloud = unidist::loadModel(models + "/torus_cloud.xyz");
  const auto* pc = dynamic_cast<const unidist::PointCloud*>(cloud.get());
  if (!pc) throw std::runtime_error("torus_cloud.xyz is not a cloud");
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  for (double shift : {3.0, 2.51, 1.0}) {
    X.translation() = Eigen::Vector3d(shift, 0, 0);
    for (int kind = 0; kind < 2; ++kind) {
      const unidist::Model& a = kind == 0 ? static_cast<const unidist::Model&>(t20) : *pc;
      const unidist::DistanceResult r = unidist::distance(a, Eigen::Isometry3d::Identity(), *pc, X);
      double brute = std::numeric_limits<double>::infinity();
      if (kind == 1)
        for (const auto& p : pc->points())
          for (const auto& q : pc->points()) brute = std::min(brute, (p - X * q).norm());
      else
        for (const auto& q : pc->points()) brute = std::min(brute, std::abs(t20.closestPoint(X * q).signedDistance));
      const double t = bench::medianMicros(51, [&] { (void)unidist::distance(a, Eigen::Isometry3d::Identity(), *pc, X); });
      std::printf("%-22s shift %-5g ours %.12g [%s, %s, %d node pairs]  brute %.12g  |  median us: ours %.1f\n",
                  kind == 0 ? "torus_20k/torus_cloud" : "torus_cloud/torus_cloud", shift, r.distance,
                  toString(r.status), r.method, r.iterations, brute, t);
    }
  }
}
