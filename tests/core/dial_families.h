// The ten pair families of the tolerance dial, each a list of posed pairs with their exact distance (how each
// truth is known: tests/core/dial_cases.h). Names are "<kind of A>-<kind of B>".
#pragma once

#include "core/dial_cases.h"

namespace dial {

inline Family primPrim(const Library& L, int n) {
  std::mt19937_64 rng(801);
  Family f{"prim-prim", {}};
  for (int i = 0; i < n; ++i) {
    f.cases.push_back(apart(rng, L.pBox, L.box, L.pCylinder, L.cylinder));
    f.cases.push_back(apart(rng, L.pCylinder, L.cylinder, L.pCone, L.cone));
    f.cases.push_back(apart(rng, L.pCone, L.cone, L.pBox, L.box));
    f.cases.push_back(apart(rng, L.pBox, L.box, L.pCapsule, L.capsule));
    f.cases.push_back(capsuleInto(rng, L, L.pBox, L.box));
    f.cases.push_back(capsuleInto(rng, L, L.pCylinder, L.cylinder));
    f.cases.push_back(capsuleInto(rng, L, L.pCone, L.cone));
  }
  return f;
}

inline Family primMesh(const Library& L, int n) {
  std::mt19937_64 rng(802);
  Family f{"prim-mesh", {}};
  for (int i = 0; i < n; ++i) {
    f.cases.push_back(apart(rng, L.pCylinder, L.cylinder, L.meshBox, L.box));
    f.cases.push_back(apart(rng, L.pCone, L.cone, L.meshBox, L.box));
    f.cases.push_back(capsuleInto(rng, L, L.meshBox, L.box));
    // The capsule beside the (non-convex) torus mesh: segment–triangle brute force, less the radius.
    drawOne(f.cases, [&]() -> std::optional<Case> {
      const Pose Xm = rotation(rng), Xc = oracle::randomPose(rng, 1.0);
      const Vec p = Xc * Vec(0, 0, -L.capsule.p1), q = Xc * Vec(0, 0, L.capsule.p1);
      const double truth = segmentMeshDistance(p, q, L.meshTorus->soup, Xm) - L.capsuleRadius;
      if (truth < 1e-3 || meshSignedDistance(L.meshTorus->soup, Xm, p) < 0) return std::nullopt;
      return makeCase("capsule-torus mesh", L.pCapsule, Xc, L.meshTorus, Xm, truth);
    });
  }
  return f;
}

inline Family primCloud(const Library& L, int n) {
  std::mt19937_64 rng(803);
  Family f{"prim-cloud", {}};
  for (int i = 0; i < n; ++i)
    for (const GeometryPtr& p : {L.pBox, L.pCylinder, L.pCone, L.pCapsule, L.pTorus}) {
      const Pose Xp = rotation(rng), Xc = at(rng, uniform(rng, 0.6, 1.3) * oracle::randomUnit(rng));
      const double truth = cloudMin(L.cloudSphere->soup, Xc, [&](const Vec& q) { return p->shape.signedDistance(Xp.inverse() * q); });
      f.cases.push_back(makeCase(p->name + "-sphere cloud", p, Xp, L.cloudSphere, Xc, truth));
    }
  return f;
}

inline Family primNurbs(const Library& L, int n) {
  std::mt19937_64 rng(804);
  Family f{"prim-nurbs", {}};
  for (int i = 0; i < n; ++i) {
    for (const GeometryPtr& p : {L.pBox, L.pCylinder, L.pCone, L.pCapsule}) {
      const Pose Xp = oracle::randomPose(rng, 0.5);
      const Vec c = beyond(rng, p->shape, Xp, 0.35, 0.9);  // depth at most 0.15 (deeper: seconds per query)
      const double truth = p->shape.signedDistance(Xp.inverse() * c) - L.sphereRadius;
      f.cases.push_back(makeCase(p->name + "-NURBS sphere", p, Xp, L.nurbsSphere, at(rng, c), truth));
    }
    const Pose Xt = rotation(rng);
    const Vec c = nearTorus(rng, L, Xt, uniform(rng, 0.4, 0.95));
    const double truth = pointCircle(c, torusCircle(L, Xt)) - L.torusA - L.ball.p0;
    f.cases.push_back(makeCase("sphere-NURBS torus", L.pBall, at(rng, c), L.nurbsTorus, Xt, truth));
  }
  return f;
}

inline Family meshMesh(const Library& L, int n) {
  std::mt19937_64 rng(805);
  Family f{"mesh-mesh", {}};
  for (int i = 0; i < n; ++i) {
    drawOne(f.cases, [&]() -> std::optional<Case> {
      const Pose Xa = rotation(rng), Xb = nearby(rng, 1.2);
      const double truth = meshMeshDistance(L.meshTorus->soup, Xa, L.meshTorus->soup, Xb);
      if (truth < 1e-3) return std::nullopt;  // touching or interpenetrating: no brute-force truth for the depth
      return makeCase("torus mesh-torus mesh", L.meshTorus, Xa, L.meshTorus, Xb, truth);
    });
    f.cases.push_back(apart(rng, L.meshBox, L.box, L.meshBox2, L.box2));
    const Pose Xa = oracle::randomPose(rng, 0.5);
    Pose Xb = rotation(rng);
    placeAtGap(L.box, Xa, L.box2, Xb, oracle::randomUnit(rng), -uniform(rng, 0.02, 0.15));
    f.cases.push_back(makeCase("grid box-grid box 2", L.meshBox, Xa, L.meshBox2, Xb, -boxBoxDepth(L.box, Xa, L.box2, Xb)));
  }
  return f;
}

inline Family meshCloud(const Library& L, int n) {
  std::mt19937_64 rng(806);
  Family f{"mesh-cloud", {}};
  for (int i = 0; i < n; ++i) {
    const Pose Xm = rotation(rng), Xc = at(rng, uniform(rng, 0.5, 1.3) * oracle::randomUnit(rng));
    const double torusTruth = cloudMin(L.cloudSphere->soup, Xc, [&](const Vec& q) { return meshSignedDistance(L.meshTorus->soup, Xm, q); });
    f.cases.push_back(makeCase("torus mesh-sphere cloud", L.meshTorus, Xm, L.cloudSphere, Xc, torusTruth));
    const Pose Xb = rotation(rng), Xt = at(rng, uniform(rng, 0.6, 1.4) * oracle::randomUnit(rng));
    const double boxTruth = cloudMin(L.cloudTorus->soup, Xt, [&](const Vec& q) { return L.box.signedDistance(Xb.inverse() * q); });
    f.cases.push_back(makeCase("grid box-torus cloud", L.meshBox, Xb, L.cloudTorus, Xt, boxTruth));
  }
  return f;
}

inline Family meshNurbs(const Library& L, int n) {
  std::mt19937_64 rng(807);
  Family f{"mesh-nurbs", {}};
  for (int i = 0; i < n; ++i) {
    const Pose Xm = oracle::randomPose(rng, 0.5);
    const Vec c = beyond(rng, L.box, Xm, 0.35, 0.9);
    f.cases.push_back(makeCase("grid box-NURBS sphere", L.meshBox, Xm, L.nurbsSphere, at(rng, c),
                               L.box.signedDistance(Xm.inverse() * c) - L.sphereRadius));
    drawOne(f.cases, [&]() -> std::optional<Case> {  // the ball beside the non-convex torus mesh
      const Pose Xt = rotation(rng);
      const Vec centre = uniform(rng, 0.5, 1.4) * oracle::randomUnit(rng);
      const double truth = meshSignedDistance(L.meshTorus->soup, Xt, centre) - L.sphereRadius;
      if (truth < 1e-3) return std::nullopt;
      return makeCase("torus mesh-NURBS sphere", L.meshTorus, Xt, L.nurbsSphere, at(rng, centre), truth);
    });
    drawOne(f.cases, [&]() -> std::optional<Case> {  // NURBS torus beside the torus mesh: circle to triangles
      const Pose Xt = rotation(rng), Xn = nearby(rng, 1.2);
      const double truth = circleMeshDistance(torusCircle(L, Xn), L.meshTorus->soup, Xt) - L.torusA;
      if (truth < 1e-3) return std::nullopt;
      return makeCase("torus mesh-NURBS torus", L.meshTorus, Xt, L.nurbsTorus, Xn, truth);
    });
  }
  return f;
}

inline Family cloudCloud(const Library& L, int n) {
  std::mt19937_64 rng(808);
  Family f{"cloud-cloud", {}};
  for (int i = 0; i < n; ++i)
    for (double reach : {0.6, 1.6}) {  // interleaved and apart
      const Pose Xa = rotation(rng), Xb = at(rng, uniform(rng, 0, reach) * oracle::randomUnit(rng));
      double truth = std::numeric_limits<double>::infinity();
      for (const Vec& p : L.cloudSphere->soup.vertices)
        for (const Vec& q : L.cloudTorus->soup.vertices) truth = std::min(truth, (Xa * p - Xb * q).norm());
      f.cases.push_back(makeCase("sphere cloud-torus cloud", L.cloudSphere, Xa, L.cloudTorus, Xb, truth));
    }
  return f;
}

inline Family cloudNurbs(const Library& L, int n) {
  std::mt19937_64 rng(809);
  Family f{"cloud-nurbs", {}};
  for (int i = 0; i < n; ++i) {
    const Pose Xc = rotation(rng), Xs = at(rng, Xc * Vec(L.torusR, 0, 0) + uniform(rng, 0.45, 1.0) * oracle::randomUnit(rng));
    const double ballTruth = cloudMin(L.cloudTorus->soup, Xc, [&](const Vec& q) { return (q - Xs.translation()).norm(); });
    f.cases.push_back(makeCase("torus cloud-NURBS sphere", L.cloudTorus, Xc, L.nurbsSphere, Xs, ballTruth - L.sphereRadius));
    const Pose Xt = rotation(rng), Xp = at(rng, Xt * Vec(L.torusR, 0, 0) + uniform(rng, 0.45, 1.0) * oracle::randomUnit(rng));
    const double torusTruth = cloudMin(L.cloudSphere->soup, Xp, [&](const Vec& q) { return pointCircle(q, torusCircle(L, Xt)); });
    f.cases.push_back(makeCase("sphere cloud-NURBS torus", L.cloudSphere, Xp, L.nurbsTorus, Xt, torusTruth - L.torusA));
  }
  return f;
}

inline Family nurbsNurbs(const Library& L, int n) {
  std::mt19937_64 rng(810);
  Family f{"nurbs-nurbs", {}};
  const double sum = L.sphereRadius + L.smallRadius;
  for (int i = 0; i < n; ++i) {
    const Pose Xa = rotation(rng), Xb = at(rng, (sum + uniform(rng, -0.1, 0.4)) * oracle::randomUnit(rng));
    f.cases.push_back(makeCase("NURBS sphere-NURBS sphere", L.nurbsSphere, Xa, L.nurbsSmall, Xb, Xb.translation().norm() - sum));
    const Pose Xt = rotation(rng), Xs = at(rng, nearTorus(rng, L, Xt, uniform(rng, 0.45, 1.1)));
    f.cases.push_back(makeCase("NURBS torus-NURBS sphere", L.nurbsTorus, Xt, L.nurbsSmall, Xs,
                               pointCircle(Xs.translation(), torusCircle(L, Xt)) - L.torusA - L.smallRadius));
    drawOne(f.cases, [&]() -> std::optional<Case> {
      const Pose Xa2 = rotation(rng), Xb2 = nearby(rng, 1.3);
      const Circle ca = torusCircle(L, Xa2), cb = torusCircle(L, Xb2);
      const double truth = nurbs_truth::circleCircle({ca.centre, ca.axis, ca.radius}, {cb.centre, cb.axis, cb.radius}) - 2 * L.torusA;
      if (truth < 1e-3) return std::nullopt;
      return makeCase("NURBS torus-NURBS torus", L.nurbsTorus, Xa2, L.nurbsTorus, Xb2, truth);
    });
  }
  return f;
}

/// The ten families by name, built on demand (the brute-force truths take a moment), `perKind` poses each.
struct FamilyBuilder {
  const char* name;
  Family (*build)(const Library&, int perKind);
};

inline std::vector<FamilyBuilder> familyBuilders() {
  return {{"prim-prim", primPrim},   {"prim-mesh", primMesh},     {"prim-cloud", primCloud}, {"prim-nurbs", primNurbs},
          {"mesh-mesh", meshMesh},   {"mesh-cloud", meshCloud},   {"mesh-nurbs", meshNurbs}, {"cloud-cloud", cloudCloud},
          {"cloud-nurbs", cloudNurbs}, {"nurbs-nurbs", nurbsNurbs}};
}

}  // namespace dial
