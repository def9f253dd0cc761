#include "unidist/bullet/scene_runner.h"

#include "eigen_bullet.h"
#include "unidist/bullet/plugin.h"
#include "unidist/bullet/shapes.h"
#include "unidist/mass.h"
#include "unidist/primitives.h"

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace unidist::bullet {
namespace {

/// One body of the world and what it needs to report the model's pose.
struct WorldBody {
  std::unique_ptr<btCollisionShape> shape;  // the unidist (or plane) shape
  std::unique_ptr<btCompoundShape> compound;  // holds `shape` at the principal-frame offset, when needed
  std::unique_ptr<btDefaultMotionState> motion;
  std::unique_ptr<btRigidBody> body;
  Eigen::Isometry3d X_BM = Eigen::Isometry3d::Identity();  // model frame in the rigid body's frame
};

/// The half-space n·x <= d of a plane model posed by X as Bullet's plane (normal, constant).
std::unique_ptr<btCollisionShape> planeShape(const Plane& plane, const Eigen::Isometry3d& X) {
  const Eigen::Vector3d n = X.linear() * plane.normal();
  const double d = plane.offset() + n.dot(X.translation());
  return std::make_unique<btStaticPlaneShape>(toBullet(n), btScalar(d));
}

WorldBody makeBody(const SceneBody& sb) {
  WorldBody wb;
  if (const auto* plane = dynamic_cast<const Plane*>(sb.model.get())) {
    if (!sb.isStatic) throw InputError(sb.name + ": a half-space must be static");
    wb.shape = planeShape(*plane, sb.pose);
    wb.motion = std::make_unique<btDefaultMotionState>();
    wb.body = std::make_unique<btRigidBody>(0, wb.motion.get(), wb.shape.get());
    wb.X_BM = sb.pose;  // the plane body sits at the origin; the model frame is the scene's pose
    return wb;
  }
  ShapeOptions options;
  options.tolerance = sb.tolerance;
  wb.shape = makeShape(sb.model, options);
  btCollisionShape* collisionShape = wb.shape.get();
  btVector3 inertia(0, 0, 0);
  Eigen::Isometry3d X_WB = sb.pose;
  if (!sb.isStatic) {
    const PrincipalInertia principal = principalInertia(massProperties(*sb.model), sb.mass);
    inertia = toBullet(principal.moments);
    wb.X_BM = principal.X_MB.inverse();
    X_WB = sb.pose * principal.X_MB;
    if (!wb.X_BM.isApprox(Eigen::Isometry3d::Identity(), 1e-12)) {
      wb.compound = std::make_unique<btCompoundShape>(false, 1);
      wb.compound->addChildShape(toBullet(wb.X_BM), wb.shape.get());
      collisionShape = wb.compound.get();
    }
  }
  wb.motion = std::make_unique<btDefaultMotionState>(toBullet(X_WB));
  btRigidBody::btRigidBodyConstructionInfo info(btScalar(sb.isStatic ? 0 : sb.mass), wb.motion.get(),
                                                collisionShape, inertia);
  info.m_friction = btScalar(sb.friction);
  info.m_restitution = btScalar(sb.restitution);
  wb.body = std::make_unique<btRigidBody>(info);
  if (!sb.isStatic) {
    wb.body->setLinearVelocity(toBullet(sb.linearVelocity));
    wb.body->setAngularVelocity(toBullet(sb.angularVelocity));
  }
  return wb;
}

/// Bullet corrects a contact deeper than m_splitImpulsePenetrationThreshold by a split impulse: a position push
/// along the normal, outside the velocity solve and so outside friction. The default, an absolute -0.04, is tuned
/// for bodies about a metre in size; in a millimetre scene every resting contact is deeper than that, and the pushes
/// along a cradled ball's tilted normals walked Bullet's own boxes off the long-run stack (docs/reliability.md,
/// "Long runs"). Scaled like ODE's surface layer: -0.02 x the smallest dynamic body's diagonal (-0.035 for a 1 m
/// cube), so resting contacts get Baumgarte's correction, inside friction, and deep impacts still the split impulse.
double splitImpulseThreshold(const Scene& scene) {
  double d = std::numeric_limits<double>::infinity();
  for (const SceneBody& b : scene.bodies)
    if (!b.isStatic && b.model && b.model->localBounds().bounded()) d = std::min(d, b.model->localBounds().diagonal());
  return -0.02 * (std::isfinite(d) ? d : 1.0);
}

BodyState stateOf(const SceneBody& sb, const WorldBody& wb) {
  BodyState s;
  s.name = sb.name;
  s.pose = toEigen(wb.body->getWorldTransform()) * wb.X_BM;
  s.linearVelocity = toEigen(wb.body->getLinearVelocity());
  s.angularVelocity = toEigen(wb.body->getAngularVelocity());
  return s;
}

/// Deepest penetration and number of contact points over every manifold of the last step.
std::pair<double, int> contactSummary(btCollisionDispatcher& dispatcher) {
  double deepest = 0;
  int count = 0;
  for (int m = 0; m < dispatcher.getNumManifolds(); ++m) {
    const btPersistentManifold* manifold = dispatcher.getManifoldByIndexInternal(m);
    for (int i = 0; i < manifold->getNumContacts(); ++i) {
      const double d = double(manifold->getContactPoint(i).getDistance());
      if (d > 0) continue;  // speculative, not touching
      ++count;
      deepest = std::max(deepest, -d);
    }
  }
  return {deepest, count};
}

/// The touching contact points of every manifold of the last step (for pictures).
std::vector<SimContact> touchingContacts(btCollisionDispatcher& dispatcher) {
  std::vector<SimContact> out;
  for (int m = 0; m < dispatcher.getNumManifolds(); ++m) {
    const btPersistentManifold* manifold = dispatcher.getManifoldByIndexInternal(m);
    for (int i = 0; i < manifold->getNumContacts(); ++i) {
      const btManifoldPoint& p = manifold->getContactPoint(i);
      if (p.getDistance() > 0) continue;
      out.push_back({0.5 * (toEigen(p.getPositionWorldOnA()) + toEigen(p.getPositionWorldOnB())),
                     toEigen(p.m_normalWorldOnB), double(p.getDistance())});
    }
  }
  return out;
}

}  // namespace

SimResult runScene(const Scene& scene, const SimOptions& options) {
  const int steps = options.steps >= 0 ? options.steps : scene.steps;
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher(&config);
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  std::unique_ptr<Registration> plugin = registerAlgorithms(&dispatcher);
  std::vector<WorldBody> bodies;
  SimResult result;
  result.engine = "bullet";
  {
    btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &config);
    world.setGravity(toBullet(scene.gravity));
    world.getSolverInfo().m_splitImpulsePenetrationThreshold = btScalar(splitImpulseThreshold(scene));
    for (const SceneBody& sb : scene.bodies) {
      bodies.push_back(makeBody(sb));
      world.addRigidBody(bodies.back().body.get());
    }
    auto states = [&] {
      std::vector<BodyState> out;
      for (std::size_t i = 0; i < bodies.size(); ++i) out.push_back(stateOf(scene.bodies[i], bodies[i]));
      return out;
    };
    double seconds = 0;  // stepping only, not the recording
    const bool frames = options.frame && options.frameEvery > 0;
    if (frames) options.frame(0, states(), {});
    for (int step = 1; step <= steps; ++step) {
      const auto start = std::chrono::steady_clock::now();
      world.stepSimulation(btScalar(scene.dt), 1, btScalar(scene.dt));
      seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const auto [deepest, count] = contactSummary(dispatcher);
      result.maxPenetration = std::max(result.maxPenetration, deepest);
      result.contacts = count;
      if (options.record && options.recordEvery > 0 && (step % options.recordEvery == 0 || step == steps))
        options.record(step, states());
      if (frames && (step % options.frameEvery == 0 || step == steps))
        options.frame(step, states(), touchingContacts(dispatcher));
    }
    result.steps = steps;
    result.stepsPerSecond = steps > 0 && seconds > 0 ? steps / seconds : 0;
    result.bodies = states();
    for (WorldBody& wb : bodies) world.removeRigidBody(wb.body.get());
  }  // the world goes first: it destroys the pair algorithms and their manifolds
  return result;
}

}  // namespace unidist::bullet
