// The side of a solid NURBS model very close to its surface: points 1e-9, 1e-11 and 1e-13 × size off faces, edges
// and corners of a box of six bilinear patches, the rational sphere's poles and seams, the torus's seams and a cube
// with a notched octant (concave edges and corners), against the analytic signed distance (sign and value).
#include "nurbs_fixtures.h"

#include "unidist/nurbs.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

namespace unidist {
namespace {

using namespace nurbs_fixtures;
using Vec = Eigen::Vector3d;

const Vec kHalf(0.45, 0.35, 0.25);

double boxDistance(const Vec& q) {
  const Vec e = q.cwiseAbs() - kHalf;
  return e.cwiseMax(0.0).norm() + std::min(e.maxCoeff(), 0.0);
}
double sphereDistance(const Vec& q) { return q.norm() - 1; }
double torusDistance(const Vec& q) { return std::hypot(std::hypot(q.x(), q.y()) - 1, q.z()) - 0.25; }

std::string num(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

constexpr double kOffsets[] = {1e-9, 1e-11, 1e-13};

/// q with each coordinate moved 0 or ±3 ulps (variant 0..26): the reported point sat 1.3e-16 inside an edge's
/// plane, and exactly placed points missed the failure.
Vec nudged(const Vec& q, int variant) {
  Vec out = q;
  constexpr double kUp = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i, variant /= 3) {
    const int move = variant % 3;  // 0: as is, 1: up, 2: down
    for (int step = 0; move != 0 && step < 3; ++step) out[i] = std::nextafter(out[i], move == 1 ? kUp : -kUp);
  }
  return out;
}

/// Sign and value of the model's answer at q and its ulp-nudged variants against the truth; the sign is checked
/// wherever the truth is above the query's own rounding (a few ulps of the coordinates).
template <class Truth>
void expectSide(const NurbsModel& m, const Vec& at, Truth truthOf, const std::string& where) {
  const double size = m.localBounds().diagonal();
  for (int variant = 0; variant < 27; ++variant) {
    const Vec q = nudged(at, variant);
    const double sd = m.closestPoint(q).signedDistance, truth = truthOf(q);
    EXPECT_NEAR(sd, truth, 2e-13 * size) << where;
    if (std::abs(truth) > 16 * std::numeric_limits<double>::epsilon() * size) {
      EXPECT_EQ(sd > 0, truth > 0) << where << ", variant " << variant << ": signed distance " << sd << ", truth "
                                   << truth;
    }
  }
}

TEST(NurbsSign, ReportedPointUnderABoxEdgeIsOutside) {
  const NurbsModel box(boxPatches(kHalf), true);
  const Vec q(-0.05, -0.34999999999999987, -0.2500000011);
  const double sd = box.closestPoint(q).signedDistance;
  EXPECT_GT(sd, 0);
  EXPECT_NEAR(sd, boxDistance(q), 1e-15);
}

TEST(NurbsSign, BoxFacesEdgesAndCorners) {
  const NurbsModel box(boxPatches(kHalf), true);
  const double size = box.localBounds().diagonal();
  for (double delta : kOffsets) {
    const double e = delta * size;
    for (int axis = 0; axis < 3; ++axis)
      for (double side : {1.0, -1.0}) {
        Vec n = Vec::Zero();
        n[axis] = side;
        // A face interior, off centre.
        Vec p = Vec(0.31, -0.17, 0.13).cwiseProduct(kHalf);
        p[axis] = side * kHalf[axis];
        for (double sign : {1.0, -1.0}) {
          const Vec q = p + sign * e * n;
          expectSide(box, q, boxDistance, "face " + std::to_string(axis) + " at " + num(delta));
        }
        // The four edges of this face (each edge twice over the faces: both orders of the normals).
        const int b = (axis + 1) % 3, c = (axis + 2) % 3;
        for (int other : {b, c})
          for (double otherSide : {1.0, -1.0}) {
            Vec m = Vec::Zero();
            m[other] = otherSide;
            Vec edge = Vec(0.37, -0.41, 0.23).cwiseProduct(kHalf);
            edge[axis] = side * kHalf[axis];
            edge[other] = otherSide * kHalf[other];
            const Vec bisector = (n + m).normalized();
            for (const Vec& dir : {Vec(n), Vec(m), bisector, Vec(-bisector), Vec(-n)}) {
              const Vec q = edge + e * dir;
              expectSide(box, q, boxDistance, "edge " + std::to_string(axis) + "/" + std::to_string(other) + " at " +
                                                     num(delta));
            }
          }
      }
    // The eight corners: along each face normal, out along the diagonal and in.
    for (int k = 0; k < 8; ++k) {
      const Vec s((k & 1) ? 1 : -1, (k & 2) ? 1 : -1, (k & 4) ? 1 : -1);
      const Vec corner = s.cwiseProduct(kHalf);
      for (const Vec& dir : {Vec(s.x(), 0, 0), Vec(0, s.y(), 0), Vec(0, 0, s.z()), Vec(s.normalized()),
                             Vec(-s.normalized())}) {
        const Vec q = corner + e * dir;
        expectSide(box, q, boxDistance, "corner " + std::to_string(k) + " at " + num(delta));
      }
    }
  }
}

TEST(NurbsSign, SpherePolesAndSeams) {
  const NurbsModel sphere({sphereSurface()}, true);
  const double size = sphere.localBounds().diagonal();
  // Poles; the seam u = 0 and the patch boundaries u = 1/4, 1/2 (meridians) and v = 1/2 (the equator), and their
  // crossings; a point off every boundary.
  std::vector<Vec> points = {Vec(0, 0, 1), Vec(0, 0, -1)};
  for (double lon : {0.0, M_PI / 2, M_PI, 0.3})
    for (double lat : {0.0, 0.6, -1.2, 1.5707})
      points.push_back(Vec(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat)));
  for (const Vec& p : points)
    for (double delta : kOffsets)
      for (double sign : {1.0, -1.0}) {
        const Vec q = p * (1 + sign * delta * size);
        expectSide(sphere, q, sphereDistance,
                   "sphere at " + num(p.x()) + " " + num(p.y()) + " " + num(p.z()) + ", " + num(sign * delta));
      }
}

TEST(NurbsSign, TorusSeamsAndEquators) {
  const NurbsModel torus({torusSurface()}, true);
  const double size = torus.localBounds().diagonal();
  // Around the axis: the seam φ = 0, the patch boundary φ = π/2 and a φ off them; around the tube: the outer
  // equator θ = 0 (the tube's seam), the top θ = π/2, the inner equator θ = π and a θ off them.
  for (double phi : {0.0, M_PI / 2, 0.7})
    for (double theta : {0.0, M_PI / 2, M_PI, 2.2})
      for (double delta : kOffsets)
        for (double sign : {1.0, -1.0}) {
          const Vec radial(std::cos(phi), std::sin(phi), 0);
          const Vec normal = std::cos(theta) * radial + Vec(0, 0, std::sin(theta));
          const Vec q = radial + 0.25 * normal + sign * delta * size * normal;
          expectSide(torus, q, torusDistance, "torus at " + std::to_string(phi) + " " + std::to_string(theta) + ", " +
                                                     num(sign * delta));
        }
}

/// The cube [−1, 1]³ without the octant [0, 1]³, of 15 bilinear squares: concave edges along the notch, a concave
/// corner at the origin, corners with convex and concave edges at (1, 0, 0) and its like.
struct NotchedCube {
  struct Square {
    Vec origin, a, b;  // axis-aligned: origin + [0,1]·a + [0,1]·b
  };
  std::vector<Square> squares;
  std::vector<NurbsSurface> surfaces;

  NotchedCube() {
    for (int axis = 0; axis < 3; ++axis) {
      const int b = (axis + 1) % 3, c = (axis + 2) % 3;
      const Vec eb = Vec::Unit(b), ec = Vec::Unit(c), n = Vec::Unit(axis);
      add(-n - eb - ec, 2 * ec, 2 * eb);  // the full −axis face, outward −axis
      for (int k = 0; k < 3; ++k) {       // the +axis face without its notched quarter
        const Vec lo = n - eb * (k == 1 ? 0 : 1) - ec * (k == 2 ? 0 : 1);
        add(lo, eb, ec);
      }
      add(Vec::Zero(), eb, ec);            // the notch's face at axis = 0, outward +axis (into the octant)
    }
  }
  void add(const Vec& origin, const Vec& a, const Vec& b) {  // a x b is the outward normal
    squares.push_back({origin, a, b});
    Net net(2);
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) {
        const Vec p = origin + i * a + j * b;
        net[static_cast<std::size_t>(i)].emplace_back(p.x(), p.y(), p.z(), 1.0);
      }
    surfaces.emplace_back(1, 1, std::vector<double>{0, 0, 1, 1}, std::vector<double>{0, 0, 1, 1}, net);
  }
  double distance(const Vec& q) const {
    double d = std::numeric_limits<double>::infinity();
    for (const Square& s : squares) {
      const double u = std::clamp((q - s.origin).dot(s.a) / s.a.squaredNorm(), 0.0, 1.0);
      const double v = std::clamp((q - s.origin).dot(s.b) / s.b.squaredNorm(), 0.0, 1.0);
      d = std::min(d, (q - s.origin - u * s.a - v * s.b).norm());
    }
    const bool inside = q.cwiseAbs().maxCoeff() < 1 && !(q.minCoeff() > 0);
    return inside ? -d : d;
  }
};

TEST(NurbsSign, ConcaveEdgesAndCorners) {
  const NotchedCube cube;
  const NurbsModel model(cube.surfaces, true);
  const auto truth = [&cube](const Vec& q) { return cube.distance(q); };
  const double size = model.localBounds().diagonal();
  const Vec x = Vec::UnitX(), y = Vec::UnitY(), z = Vec::UnitZ();
  for (double delta : kOffsets) {
    const double e = delta * size;
    // A concave edge (x = y = 0) and a convex one (x = 0, z = 1) of the notch.
    for (const Vec& dir : {Vec(x), Vec(y), Vec((x + y).normalized()), Vec(-(x + y).normalized()), Vec(-x)})
      expectSide(model, Vec(0, 0, 0.37) + e * dir, truth, "concave edge at " + num(delta));
    for (const Vec& dir : {Vec(x), Vec(z), Vec((x + z).normalized()), Vec(-(x + z).normalized()), Vec(-x)})
      expectSide(model, Vec(0, 0.61, 1) + e * dir, truth, "convex edge at " + num(delta));
    // The concave corner at the origin, and (1, 0, 0) where a concave edge meets two convex ones.
    for (const Vec& corner : {Vec(0, 0, 0), Vec(1, 0, 0)})
      for (const Vec& dir : {Vec(x), Vec(y), Vec(z), Vec(-x), Vec(-y), Vec(-z), Vec((x + y + z).normalized()),
                             Vec(-(x + y + z).normalized()), Vec((x + y - z).normalized()),
                             Vec((x - y + z).normalized()), Vec((-x + y + z).normalized())})
        expectSide(model, corner + e * dir, truth, "corner " + num(corner.x()) + " at " + num(delta));
  }
}

}  // namespace
}  // namespace unidist
