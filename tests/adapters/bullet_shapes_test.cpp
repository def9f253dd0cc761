// Bullet shapes → core models, checked against Bullet itself: for every supported shape type a native
// btSphereShape probe is placed around the native shape, Bullet's own closest-point query
// (btCollisionWorld::contactPairTest) gives the distance, and unidist::distance(probe, converted model posed
// at X_WS·X_SM) − outerMargin must agree within Bullet's float precision. This pins down sizes, axes,
// scaling and which side of the geometry each margin lies on.
#include "unidist/adapters/bullet_shapes.h"
#include "unidist/distance.h"
#include "unidist/mesh.h"
#include "unidist/primitives.h"

#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>
#include <BulletCollision/CollisionShapes/btTriangleShape.h>
#include <BulletCollision/Gimpact/btGImpactCollisionAlgorithm.h>
#include <BulletCollision/Gimpact/btGImpactShape.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btPointCollector.h>
#include <btBulletCollisionCommon.h>

#include "bullet_reference.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace {

using unidist::InputError;
using unidist::bullet::ConvertedShape;
using unidist::bullet::modelFromBulletShape;
using bullet_reference::bulletConvexDistance;

/// Through the quaternion, renormalised in double: a float basis is orthonormal only to ~1e-7, and the core
/// wants rigid poses.
Eigen::Isometry3d toEigen(const btTransform& X) {
  const btQuaternion q = X.getRotation();
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = Eigen::Quaterniond(double(q.w()), double(q.x()), double(q.y()), double(q.z())).normalized().toRotationMatrix();
  out.translation() = Eigen::Vector3d(double(X.getOrigin().x()), double(X.getOrigin().y()), double(X.getOrigin().z()));
  return out;
}

/// Bullet's closest distance for any pair, through the dispatcher a world uses (GImpact registered): the
/// convex–concave and plane algorithms, each triangle with the concave shape's margin.
double bulletWorldDistance(const btCollisionShape& a, const btTransform& X_WA, const btCollisionShape& b,
                           const btTransform& X_WB) {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher(&config);
  btGImpactCollisionAlgorithm::registerAlgorithm(&dispatcher);
  btDbvtBroadphase broadphase;
  btCollisionWorld world(&dispatcher, &broadphase, &config);
  btCollisionObject objectA, objectB;
  objectA.setCollisionShape(const_cast<btCollisionShape*>(&a));  // Bullet's API takes non-const shapes
  objectB.setCollisionShape(const_cast<btCollisionShape*>(&b));
  objectA.setWorldTransform(X_WA);
  objectB.setWorldTransform(X_WB);
  struct Closest : btCollisionWorld::ContactResultCallback {
    double best = std::numeric_limits<double>::infinity();
    btScalar addSingleResult(btManifoldPoint& p, const btCollisionObjectWrapper*, int, int, const btCollisionObjectWrapper*,
                             int, int) override {
      best = std::min(best, double(p.getDistance()));
      return 0;
    }
  } closest;
  closest.m_closestDistanceThreshold = 10;
  world.contactPairTest(&objectA, &objectB, closest);
  return closest.best;
}

/// The pose every native shape is placed at: a general rotation and an offset.
btTransform shapePose() {
  return btTransform(btQuaternion(btVector3(0.3, -1, 0.6).normalized(), 0.8), btVector3(0.7, -1.2, 2.1));
}

/// Compares Bullet and unidist for probes placed at centres given in the shape's frame. The probe is a short
/// capsule along z: its core is a segment, so Bullet's GJK meets polytopes exactly, and Bullet's special
/// sphere–triangle routine (which ignores the triangle's margin) is not involved.
void expectAgreesWithBullet(const btCollisionShape& shape, const std::vector<btVector3>& probeCentres,
                            double radius = 0.15, double tolerance = 2e-5) {
  SCOPED_TRACE(shape.getName());
  const ConvertedShape converted = modelFromBulletShape(shape);
  ASSERT_TRUE(converted.model);
  const btTransform X_WS = shapePose();
  const Eigen::Isometry3d X_WM = toEigen(X_WS) * converted.X_SM;
  const double halfLength = 0.1;
  btCapsuleShapeZ probe(btScalar(radius), btScalar(2 * halfLength));
  const unidist::Capsule probeModel(radius, halfLength);
  for (const btVector3& centre : probeCentres) {
    const btTransform X_WP(btQuaternion(btVector3(1, 1, 0).normalized(), 0.5), X_WS * centre);
    const double native = shape.isConvex() ? bulletConvexDistance(probe, X_WP, static_cast<const btConvexShape&>(shape), X_WS)
                                           : bulletWorldDistance(probe, X_WP, shape, X_WS);
    ASSERT_TRUE(std::isfinite(native)) << "Bullet reported nothing for the probe at " << centre.x() << " " << centre.y()
                                       << " " << centre.z();
    const double ours = unidist::distance(probeModel, toEigen(X_WP), *converted.model, X_WM).distance - converted.outerMargin;
    EXPECT_NEAR(ours, native, tolerance * (1 + std::abs(native)))
        << "probe at (" << centre.x() << ", " << centre.y() << ", " << centre.z() << ")";
  }
}

/// Probes around an axis-aligned shape: beyond each face centre at `reach` along ±x, ±y, ±z.
std::vector<btVector3> axisProbes(const btVector3& reach) {
  return {{reach.x(), 0.05, 0.02}, {-reach.x(), -0.03, 0.04}, {0.04, reach.y(), -0.02},
          {-0.02, -reach.y(), 0.03}, {0.03, 0.02, reach.z()}, {-0.05, 0.01, -reach.z()}};
}

/// Points written for axis z, rotated so that their third coordinate lies along `axis` (0, 1, 2).
std::vector<btVector3> alongAxis(int axis, const std::vector<btVector3>& zPoints) {
  std::vector<btVector3> out;
  for (const btVector3& p : zPoints) {
    btVector3 q;
    q[(axis + 1) % 3] = p.x();
    q[(axis + 2) % 3] = p.y();
    q[axis] = p.z();
    out.push_back(q);
  }
  return out;
}

/// Probes beyond both ends of a shape of revolution (at `axial` along its axis), near the axis.
std::vector<btVector3> endProbes(int axis, btScalar axial) {
  return alongAxis(axis, {{0.02, 0.03, axial}, {-0.03, 0.01, -axial}});
}

/// Probes beside the axis, at `radial` from it.
std::vector<btVector3> sideProbes(int axis, btScalar radial) {
  return alongAxis(axis, {{radial, 0, 0.1}, {-0.6f * radial, 0.8f * radial, -0.15}});
}

std::vector<btVector3> revolutionProbes(int axis, btScalar radial, btScalar axial) {
  std::vector<btVector3> out = endProbes(axis, axial), side = sideProbes(axis, radial);
  out.insert(out.end(), side.begin(), side.end());
  return out;
}

/// Bullet's GJK converges slowly on a curved core (the cylinder's and the cone's rims: each step moves the
/// support point along the circle) and stops on float stagnation up to ~1e-3 above the distance; against the
/// sides of those shapes the check is only that loose (a wrong margin or axis is still off by 0.04 or more).
constexpr double kCurvedGjkTolerance = 1.5e-3;

// ---- convex primitives ----------------------------------------------------------------------------------------

TEST(BulletShapes, SphereWithUniformScaling) {
  btSphereShape sphere(0.5);
  sphere.setLocalScaling(btVector3(2, 2, 2));
  expectAgreesWithBullet(sphere, {{2, 0.3, 0.2}, {-0.5, 1.6, 0.4}, {0.1, -0.2, -1.5}});
  EXPECT_DOUBLE_EQ(dynamic_cast<const unidist::Sphere&>(*modelFromBulletShape(sphere).model).radius(), 1.0);
}

TEST(BulletShapes, BoxWithScalingKeepsItsMarginInside) {
  btBoxShape box(btVector3(0.5, 1, 0.25));
  box.setLocalScaling(btVector3(1, 2, 0.5));  // half extents (0.5, 2, 0.125)
  expectAgreesWithBullet(box, axisProbes(btVector3(0.9, 2.4, 0.6)));
  // Penetrating a face: the same depth.
  expectAgreesWithBullet(box, {{0.6, 0.2, 0.05}, {0.1, 2.1, 0}});
  EXPECT_EQ(modelFromBulletShape(box).outerMargin, 0);
}

TEST(BulletShapes, CapsulesAlongEachAxis) {
  btCapsuleShapeX x(0.3, 1.2);
  btCapsuleShape y(0.3, 1.2);
  btCapsuleShapeZ z(0.3, 1.2);
  expectAgreesWithBullet(x, revolutionProbes(0, 0.8, 1.4));
  expectAgreesWithBullet(y, revolutionProbes(1, 0.8, 1.4));
  expectAgreesWithBullet(z, revolutionProbes(2, 0.8, 1.4));
  // The model's axis z is Bullet's y.
  EXPECT_TRUE(modelFromBulletShape(y).X_SM.linear().col(2).isApprox(Eigen::Vector3d::UnitY()));
  btCapsuleShape scaled(0.3, 1.2);
  scaled.setLocalScaling(btVector3(2, 0.5, 2));  // radius 0.6, half height 0.3
  expectAgreesWithBullet(scaled, revolutionProbes(1, 1.1, 1.4));
}

TEST(BulletShapes, CylindersAlongEachAxis) {
  btCylinderShapeX x(btVector3(0.8, 0.4, 0.4));
  btCylinderShape y(btVector3(0.4, 0.8, 0.4));
  btCylinderShapeZ z(btVector3(0.4, 0.4, 0.8));
  btCylinderShape scaled(btVector3(0.4, 0.8, 0.4));
  scaled.setLocalScaling(btVector3(1.5, 0.5, 1.5));  // radius 0.6, half height 0.4
  const btCylinderShape* shapes[] = {&x, &y, &z, &scaled};
  for (const btCylinderShape* c : shapes) {
    const btScalar radius = c->getRadius(), half = c->getHalfExtentsWithMargin()[c->getUpAxis()];
    expectAgreesWithBullet(*c, endProbes(c->getUpAxis(), half + 0.4f));
    expectAgreesWithBullet(*c, sideProbes(c->getUpAxis(), radius + 0.4f), 0.15, kCurvedGjkTolerance);
  }
}

TEST(BulletShapes, ConesAlongEachAxisCarryTheirMarginOutside) {
  btConeShapeX x(0.5, 1.2);
  btConeShape y(0.5, 1.2);
  btConeShapeZ z(0.5, 1.2);
  y.setMargin(0.1);  // not the default: the outer margin must follow it
  const btConeShape* shapes[] = {&x, &y, &z};
  for (const btConeShape* c : shapes) {
    expectAgreesWithBullet(*c, endProbes(c->getConeUpIndex(), 1.0));  // apex and base: exact for GJK
    expectAgreesWithBullet(*c, sideProbes(c->getConeUpIndex(), 0.9), 0.15, kCurvedGjkTolerance);
  }
  EXPECT_NEAR(modelFromBulletShape(x).outerMargin, 0.04, 1e-7);
  EXPECT_NEAR(modelFromBulletShape(y).outerMargin, 0.1, 1e-7);
}

TEST(BulletShapes, MultiSphereOfOneBallOrTwoEqualBalls) {
  const btVector3 one[] = {{0.3, -0.2, 0.5}};
  const btScalar oneRadius[] = {0.4};
  btMultiSphereShape ball(one, oneRadius, 1);
  expectAgreesWithBullet(ball, {{1.5, 0, 0.4}, {0.2, -1.4, 0.6}});
  const btVector3 two[] = {{-0.5, 0.2, 0.1}, {0.6, -0.3, 0.4}};
  const btScalar twoRadii[] = {0.25, 0.25};
  btMultiSphereShape capsule(two, twoRadii, 2);
  capsule.setLocalScaling(btVector3(1.5, 1.5, 1.5));
  expectAgreesWithBullet(capsule, {{-1.6, 0.3, 0.1}, {1.5, -0.6, 0.7}, {0, 0.9, 0.1}, {0.1, -0.2, -0.9}});
}

TEST(BulletShapes, StaticPlaneIsAHalfSpace) {
  btStaticPlaneShape plane(btVector3(0.2, 1, 0.1), 0.3);
  expectAgreesWithBullet(plane, {{0, 1.5, 0}, {2, 0.9, -1}, {-1, 0.4, 3}});
}

// ---- hulls and triangles ----------------------------------------------------------------------------------------

TEST(BulletShapes, ConvexHullIsAClosedMeshWithItsMarginOutside) {
  std::mt19937 rng(7);
  std::normal_distribution<float> gauss;
  btConvexHullShape hull;
  for (int i = 0; i < 60; ++i) {
    const btVector3 d = btVector3(gauss(rng), gauss(rng), gauss(rng)).normalized();
    hull.addPoint(btVector3(0.8f * d.x(), 0.5f * d.y(), 0.3f * d.z()), false);
  }
  hull.addPoint(btVector3(0, 0, 0), false);  // inside: not a hull vertex
  hull.recalcLocalAabb();
  hull.setLocalScaling(btVector3(1, 1.5, 2));
  const ConvertedShape converted = modelFromBulletShape(hull);
  EXPECT_TRUE(converted.model->isSolid());
  EXPECT_TRUE(converted.model->isConvex());
  EXPECT_NEAR(converted.outerMargin, 0.04, 1e-7);
  expectAgreesWithBullet(hull, axisProbes(btVector3(1.3, 1.2, 1.1)));
}

TEST(BulletShapes, FlatConvexHullIsAnOpenPolygon) {
  btConvexHullShape square;
  for (const btVector3& p : {btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(1, 1, 0), btVector3(0, 1, 0),
                             btVector3(0.5, 0.5, 0)})
    square.addPoint(p, false);
  square.recalcLocalAabb();
  const ConvertedShape converted = modelFromBulletShape(square);
  EXPECT_FALSE(converted.model->isSolid());
  expectAgreesWithBullet(square, {{0.3, 0.6, 0.7}, {0.5, 0.4, -0.6}, {1.6, 0.5, 0.1}});
}

TEST(BulletShapes, TriangleShapeIsAnOpenTriangleWithItsMargin) {
  btTriangleShape triangle(btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(0, 1, 0.2));
  EXPECT_FALSE(modelFromBulletShape(triangle).model->isSolid());
  expectAgreesWithBullet(triangle, {{0.3, 0.3, 0.8}, {0.2, 0.2, -0.7}, {1.5, -0.2, 0}, {-0.5, 0.5, 0.1}});
}

/// A closed unit cube (part 0) and a closed tetrahedron (part 1) in one vertex/index array.
struct TwoPartMesh {
  std::vector<btScalar> cubeVertices = {-0.5, -0.5, -0.5, 0.5, -0.5, -0.5, 0.5, 0.5, -0.5, -0.5, 0.5, -0.5,
                                        -0.5, -0.5, 0.5,  0.5, -0.5, 0.5,  0.5, 0.5, 0.5,  -0.5, 0.5, 0.5};
  std::vector<int> cubeIndices = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                  1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7};
  std::vector<btScalar> tetVertices = {2, 0, 0, 3, 0, 0, 2, 1, 0, 2, 0, 1};
  std::vector<short> tetIndices = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  btTriangleIndexVertexArray array;

  TwoPartMesh() {
    btIndexedMesh cube;
    cube.m_numTriangles = 12;
    cube.m_triangleIndexBase = reinterpret_cast<const unsigned char*>(cubeIndices.data());
    cube.m_triangleIndexStride = 3 * sizeof(int);
    cube.m_numVertices = 8;
    cube.m_vertexBase = reinterpret_cast<const unsigned char*>(cubeVertices.data());
    cube.m_vertexStride = 3 * sizeof(btScalar);
    array.addIndexedMesh(cube, PHY_INTEGER);
    btIndexedMesh tet;
    tet.m_numTriangles = 4;
    tet.m_triangleIndexBase = reinterpret_cast<const unsigned char*>(tetIndices.data());
    tet.m_triangleIndexStride = 3 * sizeof(short);
    tet.m_numVertices = 4;
    tet.m_vertexBase = reinterpret_cast<const unsigned char*>(tetVertices.data());
    tet.m_vertexStride = 3 * sizeof(btScalar);
    array.addIndexedMesh(tet, PHY_SHORT);
  }
};

// Probes near the cube's faces (in mesh coordinates before scaling) and near the tetrahedron's slanted face.
std::vector<btVector3> twoPartProbes(const btVector3& scale) {
  std::vector<btVector3> out;
  for (const btVector3& p : {btVector3(-0.9, 0.1, 0.05), btVector3(0.1, 0.8, -0.1), btVector3(0.05, -0.1, -0.85),
                             btVector3(2.6, 0.6, 0.6)})
    out.push_back(p * scale);
  return out;
}

TEST(BulletShapes, BvhTriangleMeshKeepsEveryPartAndIsSolidWhenClosed) {
  TwoPartMesh mesh;
  btBvhTriangleMeshShape shape(&mesh.array, true);
  const ConvertedShape converted = modelFromBulletShape(shape);
  EXPECT_TRUE(converted.model->isSolid());
  EXPECT_EQ(dynamic_cast<const unidist::TriangleMesh&>(*converted.model).triangles().size(), 16u);
  expectAgreesWithBullet(shape, twoPartProbes(btVector3(1, 1, 1)));

  shape.setLocalScaling(btVector3(1, 1.5, 0.8));
  expectAgreesWithBullet(shape, twoPartProbes(btVector3(1, 1.5, 0.8)));

  btScaledBvhTriangleMeshShape scaled(&shape, btVector3(2, 1, 1));  // on top of the child's own scaling
  expectAgreesWithBullet(scaled, twoPartProbes(btVector3(2, 1.5, 0.8)));
}

TEST(BulletShapes, OpenBvhMeshIsAnOpenSurface) {
  TwoPartMesh mesh;
  mesh.array.getIndexedMeshArray()[0].m_numTriangles = 10;  // the cube loses its -x face
  btBvhTriangleMeshShape shape(&mesh.array, true);
  shape.setMargin(0.05);
  const ConvertedShape converted = modelFromBulletShape(shape);
  EXPECT_FALSE(converted.model->isSolid());
  EXPECT_NEAR(converted.outerMargin, 0.05, 1e-7);
  expectAgreesWithBullet(shape, twoPartProbes(btVector3(1, 1, 1)));
}

TEST(BulletShapes, GImpactMeshUsesItsPartsScalingAndMargin) {
  TwoPartMesh mesh;
  btGImpactMeshShape shape(&mesh.array);
  shape.setLocalScaling(btVector3(1.2, 1, 1));
  shape.setMargin(0.02);
  shape.updateBound();
  const ConvertedShape converted = modelFromBulletShape(shape);
  EXPECT_TRUE(converted.model->isSolid());
  EXPECT_NEAR(converted.outerMargin, 0.02, 1e-7);
  // GImpact pairs only triangles whose boxes overlap the probe's: probes close to the surface.
  expectAgreesWithBullet(shape, {{-0.75, 0.1, 0.05}, {0.1, 0.72, -0.1}, {2.9, 0.4, 0.4}});
}

TEST(BulletShapes, HeightfieldIsAnOpenMeshOfItsGrid) {
  const int width = 6, length = 5;
  std::vector<float> heights;
  for (int j = 0; j < length; ++j)
    for (int i = 0; i < width; ++i) heights.push_back(0.3f * std::sin(0.9f * i) * std::cos(0.7f * j) + 0.05f * i);
  btHeightfieldTerrainShape terrain(width, length, heights.data(), 1, -0.5f, 0.6f, 1, PHY_FLOAT, false);
  terrain.setLocalScaling(btVector3(0.5, 1, 0.4));
  const ConvertedShape converted = modelFromBulletShape(terrain);
  EXPECT_FALSE(converted.model->isSolid());
  EXPECT_EQ(dynamic_cast<const unidist::TriangleMesh&>(*converted.model).triangles().size(), 2u * (width - 1) * (length - 1));
  expectAgreesWithBullet(terrain, {{0, 0.6, 0}, {0.6, 0.5, -0.3}, {-0.7, 0.4, 0.5}, {1.1, 0.7, 0.6}});
}

// ---- bad input ------------------------------------------------------------------------------------------------

void expectInputError(const btCollisionShape& shape, const std::vector<std::string>& words) {
  try {
    modelFromBulletShape(shape);
    ADD_FAILURE() << "no InputError for " << shape.getName();
  } catch (const InputError& e) {
    for (const std::string& w : words) EXPECT_NE(std::string(e.what()).find(w), std::string::npos) << e.what();
  }
}

TEST(BulletShapes, RejectsWhatUnidistCannotRepresent) {
  btSphereShape sphere(1);
  sphere.setLocalScaling(btVector3(1, 2, 1));
  expectInputError(sphere, {"btSphereShape", "non-uniform"});

  btCapsuleShape capsule(0.3, 1);
  capsule.setLocalScaling(btVector3(1, 1, 2));
  expectInputError(capsule, {"btCapsuleShape", "radial"});

  btCylinderShape elliptic(btVector3(0.3, 1, 0.5));
  expectInputError(elliptic, {"btCylinderShape", "elliptic"});

  btCompoundShape compound;
  btBoxShape child(btVector3(1, 1, 1));
  compound.addChildShape(btTransform::getIdentity(), &child);
  expectInputError(compound, {"btCompoundShape", "recurses"});

  const btVector3 centres[] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const btScalar radii[] = {0.1f, 0.1f, 0.1f};
  btMultiSphereShape three(centres, radii, 3);
  expectInputError(three, {"btMultiSphereShape", "3 balls"});

  btConvexHullShape line;
  line.addPoint(btVector3(0, 0, 0));
  line.addPoint(btVector3(1, 1, 1));
  line.addPoint(btVector3(2, 2, 2));
  expectInputError(line, {"btConvexHullShape"});

  btStaticPlaneShape plane(btVector3(0, 0, 1), 0);
  plane.setLocalScaling(btVector3(2, 2, 2));
  expectInputError(plane, {"btStaticPlaneShape", "scaling"});
}

}  // namespace
