// ODE scene runner (unidist/ode/scene_runner.h).
#include "unidist/ode/scene_runner.h"

#include "unidist/adapters/ode_geoms.h"
#include "unidist/mass.h"
#include "unidist/ode/geom.h"
#include "unidist/primitives.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <vector>

namespace unidist::ode {
namespace {

constexpr int kMaxContactsPerPair = 8;

struct RunnerBody {
  dBodyID body = nullptr;
  dGeomID geom = nullptr;
  Eigen::Isometry3d X_BM = Eigen::Isometry3d::Identity();  // model frame in the ODE body frame
  double friction = 0.5, restitution = 0;
};

struct World {
  dWorldID world = nullptr;
  dSpaceID space = nullptr;
  dJointGroupID contactGroup = nullptr;
  std::vector<RunnerBody> bodies;
  double maxDepth = 0;
  int contactsThisStep = 0;
  double bounceVelocity = 0;
  bool keepContacts = false;           // this step is pictured: keep its contact points
  std::vector<SimContact> stepContacts;
};

void toOde(const Eigen::Matrix3d& R, dMatrix3 out) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) out[4 * i + j] = R(i, j);
    out[4 * i + 3] = 0;
  }
}

Eigen::Isometry3d bodyPose(dBodyID b) {
  const dReal* p = dBodyGetPosition(b);
  const dReal* R = dBodyGetRotation(b);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) X.linear()(i, j) = R[4 * i + j];
  X.translation() = Eigen::Vector3d(p[0], p[1], p[2]);
  return X;
}

/// A static half-space as ODE's plane: n·x <= d in the model frame, moved by the body's pose.
dGeomID staticPlane(dSpaceID space, const Plane& plane, const Eigen::Isometry3d& X_WM) {
  const Eigen::Vector3d n = X_WM.linear() * plane.normal();
  const double d = plane.offset() + n.dot(X_WM.translation());
  return dCreatePlane(space, n.x(), n.y(), n.z(), d);
}

RunnerBody addDynamic(World& w, const SceneBody& sb) {
  if (!(sb.mass > 0)) throw InputError("ODE scene runner: body '" + sb.name + "' needs a mass > 0");
  const PrincipalInertia pi = principalInertia(massProperties(*sb.model), sb.mass);
  RunnerBody rb;
  rb.body = dBodyCreate(w.world);
  const Eigen::Isometry3d X_WB = sb.pose * pi.X_MB;
  dBodySetPosition(rb.body, X_WB.translation().x(), X_WB.translation().y(), X_WB.translation().z());
  dMatrix3 R;
  toOde(X_WB.linear(), R);
  dBodySetRotation(rb.body, R);
  dMass m;
  dMassSetZero(&m);
  dMassSetParameters(&m, sb.mass, 0, 0, 0, pi.moments.x(), pi.moments.y(), pi.moments.z(), 0, 0, 0);
  dBodySetMass(rb.body, &m);
  dBodySetLinearVel(rb.body, sb.linearVelocity.x(), sb.linearVelocity.y(), sb.linearVelocity.z());
  dBodySetAngularVel(rb.body, sb.angularVelocity.x(), sb.angularVelocity.y(), sb.angularVelocity.z());

  rb.geom = createGeom(w.space, sb.model);
  dGeomSetBody(rb.geom, rb.body);
  rb.X_BM = pi.X_MB.inverse();
  dGeomSetOffsetPosition(rb.geom, rb.X_BM.translation().x(), rb.X_BM.translation().y(), rb.X_BM.translation().z());
  toOde(rb.X_BM.linear(), R);
  dGeomSetOffsetRotation(rb.geom, R);
  return rb;
}

RunnerBody addBody(World& w, const SceneBody& sb) {
  if (!sb.model) throw InputError("ODE scene runner: body '" + sb.name + "' has no model");
  const bool isPlane = sb.model->type() == ModelType::Plane;
  if (isPlane && !sb.isStatic) throw InputError("ODE scene runner: half-space body '" + sb.name + "' must be static");
  RunnerBody rb;
  if (isPlane) {
    rb.geom = staticPlane(w.space, static_cast<const Plane&>(*sb.model), sb.pose);
  } else if (sb.isStatic) {
    rb.geom = createGeom(w.space, sb.model);
    dGeomSetPosition(rb.geom, sb.pose.translation().x(), sb.pose.translation().y(), sb.pose.translation().z());
    dMatrix3 R;
    toOde(sb.pose.linear(), R);
    dGeomSetRotation(rb.geom, R);
  } else {
    rb = addDynamic(w, sb);
  }
  if (!isPlane && sb.tolerance > 0) setTolerance(rb.geom, sb.tolerance);
  rb.friction = sb.friction;
  rb.restitution = sb.restitution;
  return rb;
}

void nearCallback(void* data, dGeomID o1, dGeomID o2) {
  World& w = *static_cast<World*>(data);
  dBodyID b1 = dGeomGetBody(o1), b2 = dGeomGetBody(o2);
  if (!b1 && !b2) return;
  if (b1 && b2 && dAreConnectedExcluding(b1, b2, dJointTypeContact)) return;
  dContact c[kMaxContactsPerPair];
  const int n = dCollide(o1, o2, kMaxContactsPerPair, &c[0].geom, sizeof(dContact));
  if (n <= 0) return;
  const RunnerBody& r1 = w.bodies[reinterpret_cast<std::size_t>(dGeomGetData(o1))];
  const RunnerBody& r2 = w.bodies[reinterpret_cast<std::size_t>(dGeomGetData(o2))];
  const double mu = std::sqrt(r1.friction * r2.friction);
  const double bounce = std::max(r1.restitution, r2.restitution);
  for (int i = 0; i < n; ++i) {
    c[i].surface.mode = dContactApprox1 | (bounce > 0 ? dContactBounce : 0);
    c[i].surface.mu = mu;
    c[i].surface.bounce = bounce;
    c[i].surface.bounce_vel = w.bounceVelocity;
    w.maxDepth = std::max(w.maxDepth, static_cast<double>(c[i].geom.depth));
    if (w.keepContacts)
      w.stepContacts.push_back({Eigen::Vector3d(c[i].geom.pos[0], c[i].geom.pos[1], c[i].geom.pos[2]),
                                Eigen::Vector3d(c[i].geom.normal[0], c[i].geom.normal[1], c[i].geom.normal[2]),
                                -static_cast<double>(c[i].geom.depth)});
    dJointAttach(dJointCreateContact(w.world, w.contactGroup, &c[i]), dGeomGetBody(c[i].geom.g1),
                 dGeomGetBody(c[i].geom.g2));
  }
  w.contactsThisStep += n;
}

std::vector<BodyState> states(const Scene& scene, const World& w) {
  std::vector<BodyState> out;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const SceneBody& sb = scene.bodies[i];
    const RunnerBody& rb = w.bodies[i];
    BodyState s;
    s.name = sb.name;
    s.pose = sb.pose;
    if (rb.body) {
      s.pose = bodyPose(rb.body) * rb.X_BM;
      const dReal* v = dBodyGetLinearVel(rb.body);
      const dReal* a = dBodyGetAngularVel(rb.body);
      s.linearVelocity = Eigen::Vector3d(v[0], v[1], v[2]);
      s.angularVelocity = Eigen::Vector3d(a[0], a[1], a[2]);
    }
    out.push_back(s);
  }
  return out;
}

double smallestDynamicDiagonal(const Scene& scene) {
  double d = std::numeric_limits<double>::infinity();
  for (const SceneBody& b : scene.bodies)
    if (!b.isStatic && b.model && b.model->localBounds().bounded()) d = std::min(d, b.model->localBounds().diagonal());
  return std::isfinite(d) ? d : 1;
}

/// Owns the ODE objects of one run; destroys them (and closes this run's ODE initialisation) on every exit path.
struct OdeRun {
  World w;
  dThreadingImplementationID threading = nullptr;
  /// ODE counts dInitODE2/dCloseODE in a plain integer: runs in several threads must not race on it (a lost
  /// decrement would close ODE under another thread's world).
  static std::mutex& initMutex() {
    static std::mutex m;
    return m;
  }
  OdeRun() {
    {
      std::lock_guard<std::mutex> lock(initMutex());
      dInitODE2(0);
      dAllocateODEDataForThread(dAllocateMaskAll);  // this thread's collision data (ODE builds with TLS need it)
      init();
    }
    w.world = dWorldCreate();
    // The world's own stepping threading: without one, every world of the process shares ODE's default
    // implementation, and worlds stepped in parallel threads corrupt its job list (ODE INTERNAL ERROR, abort).
    threading = dThreadingAllocateSelfThreadedImplementation();
    dWorldSetStepThreadingImplementation(w.world, dThreadingImplementationGetFunctions(threading), threading);
    w.space = dHashSpaceCreate(nullptr);
    w.contactGroup = dJointGroupCreate(0);
  }
  ~OdeRun() {
    dJointGroupDestroy(w.contactGroup);
    dSpaceDestroy(w.space);  // destroys the geoms it holds (cleanup mode on)
    dWorldDestroy(w.world);  // destroys the bodies
    dThreadingFreeImplementation(threading);
    std::lock_guard<std::mutex> lock(initMutex());
    dCloseODE();
  }
  OdeRun(const OdeRun&) = delete;
  OdeRun& operator=(const OdeRun&) = delete;
};

}  // namespace

SimResult runScene(const Scene& scene, const SimOptions& options) {
  if (!(scene.dt > 0) || !std::isfinite(scene.dt)) throw InputError("ODE scene runner: dt must be finite and > 0");
  OdeRun run;
  World& w = run.w;
  dWorldSetGravity(w.world, scene.gravity.x(), scene.gravity.y(), scene.gravity.z());
  dWorldSetContactSurfaceLayer(w.world, 1e-4 * smallestDynamicDiagonal(scene));
  w.bounceVelocity = 2 * scene.gravity.norm() * scene.dt;  // slower impacts are resting contacts, not bounces
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    w.bodies.push_back(addBody(w, scene.bodies[i]));
    dGeomSetData(w.bodies.back().geom, reinterpret_cast<void*>(i));
  }

  const int steps = options.steps >= 0 ? options.steps : scene.steps;
  SimResult result;
  result.engine = "ode";
  result.steps = steps;
  const auto start = std::chrono::steady_clock::now();
  double recordSeconds = 0;
  const bool frames = options.frame && options.frameEvery > 0;
  auto timed = [&recordSeconds](const auto& call) {  // recording is not stepping
    const auto r0 = std::chrono::steady_clock::now();
    call();
    recordSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - r0).count();
  };
  if (frames) timed([&] { options.frame(0, states(scene, w), {}); });
  for (int step = 1; step <= steps; ++step) {
    w.contactsThisStep = 0;
    w.keepContacts = frames && (step % options.frameEvery == 0 || step == steps);
    w.stepContacts.clear();
    dSpaceCollide(w.space, &w, &nearCallback);
    dWorldStep(w.world, scene.dt);
    dJointGroupEmpty(w.contactGroup);
    if (options.record && options.recordEvery > 0 && (step % options.recordEvery == 0 || step == steps))
      timed([&] { options.record(step, states(scene, w)); });
    if (w.keepContacts) timed([&] { options.frame(step, states(scene, w), w.stepContacts); });
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() - recordSeconds;
  result.bodies = states(scene, w);
  result.maxPenetration = w.maxDepth;
  result.contacts = w.contactsThisStep;
  result.stepsPerSecond = seconds > 0 ? steps / seconds : 0;
  return result;
}

}  // namespace unidist::ode
