// ODE plugin throughput: steps per second of an ordinary ODE loop (dSpaceCollide → dCollide →
// dJointCreateContact → dWorldQuickStep) for (1) 50 mixed unidist bodies (spheres, boxes, mesh boxes, point-cloud
// boxes, cylinders, and capsules or tori) dropped on a dCreatePlane, and (2) the same 50-box pile once as unidist box primitives
// and once as ODE's native dBox (ODE's own box–box and box–plane colliders), same poses, same loop. Each
// configuration runs `runs` times; the median steps/s is reported with the ratio native / unidist.
// Usage: unidist_bench_ode [steps=600] [runs=3] [boxes]   (CSV on stdout; "boxes": the box cases only)
#include "median.h"
#include "plugin/models.h"
#include "unidist/mesh.h"
#include "unidist/ode/geom.h"
#include "unidist/point_cloud.h"
#include "unidist/primitives.h"

#include <ode/ode.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace {

using Vec = Eigen::Vector3d;
using ModelPtr = std::shared_ptr<const unidist::Model>;

/// A box [-h, h]^3 as a 12-triangle mesh and as the lattice of its faces (a point cloud).
ModelPtr meshBox(double h) { return test_models::meshBox(Vec(h, h, h), 1); }
ModelPtr cloudBox(double h) { return test_models::cloudBox(Vec(h, h, h), 4); }

/// One body to create: its geom (made in the given space) and its ODE mass.
struct BodySpec {
  std::function<dGeomID(dSpaceID)> makeGeom;
  dMass mass;
  Vec at;
};

struct Loop {
  dWorldID world;
  dJointGroupID group;
};

void nearCallback(void* data, dGeomID o1, dGeomID o2) {
  const Loop& loop = *static_cast<Loop*>(data);
  dBodyID b1 = dGeomGetBody(o1), b2 = dGeomGetBody(o2);
  if (!b1 && !b2) return;
  dContact c[8];
  const int n = dCollide(o1, o2, 8, &c[0].geom, sizeof(dContact));
  for (int i = 0; i < n; ++i) {
    c[i].surface.mode = dContactApprox1;
    c[i].surface.mu = 0.6;
    dJointAttach(dJointCreateContact(loop.world, loop.group, &c[i]), dGeomGetBody(c[i].geom.g1), dGeomGetBody(c[i].geom.g2));
  }
}

/// Steps per second of one run (collision + solver, wall clock).
double run(const std::vector<BodySpec>& specs, int steps) {
  dInitODE2(0);
  unidist::ode::init();
  Loop loop{dWorldCreate(), dJointGroupCreate(0)};
  dSpaceID space = dHashSpaceCreate(nullptr);
  dWorldSetGravity(loop.world, 0, 0, -9.81);
  dWorldSetContactSurfaceLayer(loop.world, 1e-4);
  dCreatePlane(space, 0, 0, 1, 0);
  for (const BodySpec& s : specs) {
    dGeomID g = s.makeGeom(space);
    dBodyID b = dBodyCreate(loop.world);
    dBodySetMass(b, &s.mass);
    dBodySetPosition(b, s.at.x(), s.at.y(), s.at.z());
    dGeomSetBody(g, b);
  }
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < steps; ++i) {
    dSpaceCollide(space, &loop, &nearCallback);
    dWorldQuickStep(loop.world, 1.0 / 240);
    dJointGroupEmpty(loop.group);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  dJointGroupDestroy(loop.group);
  dSpaceDestroy(space);
  dWorldDestroy(loop.world);
  dCloseODE();
  return steps / seconds;
}

/// A 5 x 5 grid, two layers, with a small offset per body so that the pile is not perfectly regular.
Vec slot(int i, double spacing) {
  return Vec(spacing * (i % 5 - 2) + 0.01 * (i % 3), spacing * ((i / 5) % 5 - 2), 0.6 + 1.2 * (i / 25));
}

/// withTori = false puts capsules where the tori were (mesh–torus contacts take seconds per query in the core).
std::vector<BodySpec> mixedBodies(bool withTori) {
  std::vector<BodySpec> out;
  for (int i = 0; i < 50; ++i) {
    BodySpec s;
    s.at = slot(i, 1.3);
    ModelPtr m;
    switch (i % 6) {
      case 0: m = std::make_shared<unidist::Sphere>(0.4); dMassSetSphereTotal(&s.mass, 1, 0.4); break;
      case 1: m = std::make_shared<unidist::Box>(Vec(0.4, 0.3, 0.3)); dMassSetBoxTotal(&s.mass, 1, 0.8, 0.6, 0.6); break;
      case 2: m = meshBox(0.35); dMassSetBoxTotal(&s.mass, 1, 0.7, 0.7, 0.7); break;
      case 3: m = cloudBox(0.3); dMassSetBoxTotal(&s.mass, 1, 0.6, 0.6, 0.6); break;
      case 4: m = std::make_shared<unidist::Cylinder>(0.35, 0.25); dMassSetCylinderTotal(&s.mass, 1, 3, 0.35, 0.5); break;
      default:
        if (!withTori) {
          m = std::make_shared<unidist::Capsule>(0.25, 0.2);
          dMassSetCapsuleTotal(&s.mass, 1, 3, 0.25, 0.4);
          break;
        }
        m = std::make_shared<unidist::Torus>(0.4, 0.12);
        dMassSetParameters(&s.mass, 1, 0, 0, 0, 0.09, 0.09, 0.17, 0, 0, 0);
        break;
    }
    s.makeGeom = [m](dSpaceID sp) { return unidist::ode::createGeom(sp, m); };
    out.push_back(s);
  }
  return out;
}

std::vector<BodySpec> boxes(bool native) {
  std::vector<BodySpec> out;
  const auto model = std::make_shared<unidist::Box>(Vec(0.4, 0.3, 0.3));
  for (int i = 0; i < 50; ++i) {
    BodySpec s;
    s.at = slot(i, 1.0);
    dMassSetBoxTotal(&s.mass, 1, 0.8, 0.6, 0.6);
    if (native)
      s.makeGeom = [](dSpaceID sp) { return dCreateBox(sp, 0.8, 0.6, 0.6); };
    else
      s.makeGeom = [model](dSpaceID sp) { return unidist::ode::createGeom(sp, model); };
    out.push_back(s);
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  const int steps = argc > 1 ? std::atoi(argv[1]) : 600;
  const int runs = argc > 2 ? std::atoi(argv[2]) : 3;
  const bool boxesOnly = argc > 3 && std::string(argv[3]) == "boxes";
  std::vector<double> mixed{0}, mixedTori{0}, unidistBoxes, nativeBoxes;
  for (int r = 0; r < runs; ++r) {
    if (!boxesOnly) {
      mixed.push_back(run(mixedBodies(false), steps));
      mixedTori.push_back(run(mixedBodies(true), steps));
    }
    unidistBoxes.push_back(run(boxes(false), steps));  // interleaved: both see the same machine load
    nativeBoxes.push_back(run(boxes(true), steps));
  }
  std::printf("case,bodies,steps,runs,median_steps_per_s\n");
  if (!boxesOnly) {
    mixed.erase(mixed.begin());
    mixedTori.erase(mixedTori.begin());
    std::printf("mixed_unidist,50,%d,%d,%.1f\n", steps, runs, median(mixed));
    std::printf("mixed_unidist_with_tori,50,%d,%d,%.1f\n", steps, runs, median(mixedTori));
  }
  std::printf("boxes_unidist,50,%d,%d,%.1f\n", steps, runs, median(unidistBoxes));
  std::printf("boxes_ode_native,50,%d,%d,%.1f\n", steps, runs, median(nativeBoxes));
  std::printf("# native / unidist box ratio: %.2f\n", median(nativeBoxes) / median(unidistBoxes));
  return 0;
}
