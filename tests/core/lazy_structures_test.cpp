// Acceleration structures are built on first need, once, and only for what a query uses (issue 8): the
// counters of Model::structures() before and after each kind of query.
#include "core/mesh_fixtures.h"
#include "core/query_helpers.h"
#include "unidist/contacts.h"
#include "unidist/distance.h"
#include "unidist/mesh.h"
#include "unidist/point_cloud.h"
#include "unidist/primitives.h"

#include <gtest/gtest.h>

#include <string>

namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;
using query_test::structureBuilt;

Isometry3d at(const Vector3d& t) { return query_test::translation(t); }

std::size_t bytesOf(const unidist::Model& m, const std::string& name) {
  for (const unidist::StructureReport& s : m.structures())
    if (s.name == name) return s.bytes;
  return 0;
}

TEST(LazyStructures, AFreshModelHasBuiltNothing) {
  const unidist::TriangleMesh mesh = meshfix::makeMesh(meshfix::torus(1, 0.25, 32, 12));
  EXPECT_FALSE(structureBuilt(mesh, "bvh"));
  EXPECT_FALSE(structureBuilt(mesh, "winding"));
  EXPECT_EQ(bytesOf(mesh, "bvh"), 0u);
  const unidist::Box box(Vector3d(1, 1, 1));
  EXPECT_FALSE(structureBuilt(box, "contact-mesh"));
  const unidist::PointCloud cloud(meshfix::icosphere(1, 2).vertices);
  EXPECT_FALSE(structureBuilt(cloud, "point-tree"));
}

TEST(LazyStructures, DistanceBuildsTheHierarchyButNotTheWindingData) {
  const unidist::TriangleMesh a = meshfix::makeMesh(meshfix::torus(1, 0.25, 32, 12));
  const unidist::TriangleMesh b = meshfix::makeMesh(meshfix::torus(1, 0.25, 32, 12));
  const std::size_t before = a.memoryBytes();
  unidist::distance(a, Isometry3d::Identity(), b, at(Vector3d(3, 0, 0)));  // apart
  EXPECT_TRUE(structureBuilt(a, "bvh"));
  EXPECT_FALSE(structureBuilt(a, "winding"));  // no point far inside was asked about
  EXPECT_EQ(a.bvhBuildCount(), 1);
  EXPECT_EQ(a.memoryBytes(), before + bytesOf(a, "bvh"));
  unidist::distance(a, Isometry3d::Identity(), b, at(Vector3d(2.5, 0.1, 0)));
  EXPECT_EQ(a.bvhBuildCount(), 1);  // once
}

TEST(LazyStructures, BoxDistancesNeverBuildTheContactMesh) {
  const unidist::Box a(Vector3d(1, 1, 1)), b(Vector3d(0.5, 0.5, 0.5));
  for (double x : {3.0, 1.4, 0.5}) unidist::distance(a, Isometry3d::Identity(), b, at(Vector3d(x, 0, 0)));
  EXPECT_FALSE(structureBuilt(a, "contact-mesh"));
  EXPECT_FALSE(structureBuilt(b, "contact-mesh"));
  unidist::contacts(a, Isometry3d::Identity(), b, at(Vector3d(1.4, 0, 0)));  // a contact set works on the mesh
  EXPECT_TRUE(structureBuilt(a, "contact-mesh"));
}

TEST(LazyStructures, OverlapOfASphereWithACloudOnlyNeedsThePointTree) {
  const unidist::PointCloud cloud(meshfix::icosphere(1, 2).vertices);
  const unidist::Sphere ball(0.5);
  unidist::DistanceOptions o;
  o.compute = unidist::Compute::Overlap;
  unidist::distance(ball, Isometry3d::Identity(), cloud, at(Vector3d(0, 0, 3)), o);
  EXPECT_TRUE(structureBuilt(cloud, "point-tree"));
}

TEST(LazyStructures, BuildStructuresBuildsEverythingOnce) {
  const unidist::TriangleMesh mesh = meshfix::makeMesh(meshfix::torus(1, 0.25, 32, 12));
  mesh.buildStructures();
  mesh.buildStructures();
  EXPECT_TRUE(structureBuilt(mesh, "bvh"));
  EXPECT_TRUE(structureBuilt(mesh, "winding"));
  EXPECT_GT(bytesOf(mesh, "winding"), 0u);
  EXPECT_EQ(mesh.bvhBuildCount(), 1);
}

}  // namespace
