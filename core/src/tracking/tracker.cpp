// unidist::Tracker (unidist/tracker.h): the per-update loop (local updates, global pass policy, merging,
// dropping) and the penalty forces.
#include "unidist/tracker.h"

#include "contacts/pair_motion.h"
#include "tracking/local_update.h"
#include "unidist/contacts.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <future>
#include <limits>

namespace unidist {
namespace {

using tracking::LocalMinimum;
using tracking::LocalUpdater;
using contact::boundedDiagonal;
using contact::relativeMotion;

TrackerOptions resolve(const Model& a, const Model& b, TrackerOptions o) {
  auto bad = [](const char* what) { throw InputError(std::string("Tracker: ") + what); };
  const double size = std::min(boundedDiagonal(a), boundedDiagonal(b));
  if (!std::isfinite(size)) bad("two unbounded models");
  if (std::isnan(o.tolerance) || !std::isfinite(o.cutoff) || !std::isfinite(o.guard) ||
      !std::isfinite(o.penaltyDistance))
    bad("tolerance, cutoff, guard and penaltyDistance must be finite");
  if (o.globalPeriod <= 0) bad("globalPeriod must be > 0");
  if (!(o.stiffness >= 0) || !(o.damping >= 0) || !std::isfinite(o.stiffness) || !std::isfinite(o.damping))
    bad("stiffness and damping must be finite and >= 0");
  if (!(o.timeStep > 0) || !std::isfinite(o.timeStep)) bad("timeStep must be finite and > 0");
  if (o.maxLocalIterations <= 0) bad("maxLocalIterations must be > 0");
  if (!o.referencePoint_A.allFinite()) bad("referencePoint_A must be finite");
  o.tolerance = o.tolerance < 0 ? 1e-6 * size : std::max(o.tolerance, 1e-12 * size);
  if (o.cutoff < 0) o.cutoff = 0.02 * size;
  if (o.guard < 0) o.guard = o.cutoff > 0 ? o.cutoff : 0.02 * size;
  if (o.penaltyDistance < 0) o.penaltyDistance = o.cutoff;
  if (o.penaltyDistance > o.cutoff) bad("penaltyDistance must be <= cutoff");
  return o;
}

/// The global pass: every local minimum within the grown margin at relative pose X_AB (A's frame is the world),
/// turned into the tracker's form. Runs on the caller's thread or a worker; touches only const state.
std::vector<LocalMinimum> globalPass(const Model& a, const Model& b, const LocalUpdater& updater,
                                     const TrackerOptions& o, const Eigen::Isometry3d& X_AB) {
  ContactOptions co;
  static_cast<QueryOptions&>(co) = o;
  co.detailA = co.detailB = 0;  // a and b are already the models at their levels of detail
  co.margin = o.cutoff + 2 * o.guard;
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  std::vector<LocalMinimum> out;
  for (const Contact& c : contacts(a, I, b, X_AB, co))
    out.push_back(updater.fromWorld(c.pointA, c.pointB, c.distance, c.normal, I, X_AB));
  return out;
}

struct Track {
  LocalMinimum m;
  long id = 0, age = 0;
  double previous = 0;  // distance at the previous update (for the damping)
  bool hasPrevious = false;
};

}  // namespace

struct Tracker::Impl {
  std::shared_ptr<const Model> ownerA, ownerB;
  const Model& a;  // the models at their levels of detail (their stand-ins live as long as the owners)
  const Model& b;
  TrackerOptions options;
  LocalUpdater updater;
  double mergeDistance;
  std::vector<Track> tracks;
  std::vector<TrackedMinimum> minima;
  TrackerUpdate last;
  TrackerCounters counters;
  Eigen::Isometry3d previousX_AB = Eigen::Isometry3d::Identity();  // pose of the last update (the damping's jump test)
  bool hasPreviousPose = false;
  long nextId = 1;
  // Global pass state: the relative pose and update count of the last pass started, and the pass in flight.
  bool passed = false;
  Eigen::Isometry3d X_ABpass = Eigen::Isometry3d::Identity();
  long updatesSincePass = 0;
  std::future<std::vector<LocalMinimum>> pending;

  Impl(std::shared_ptr<const Model> a0, std::shared_ptr<const Model> b0, const TrackerOptions& o)
      : ownerA(std::move(a0)), ownerB(std::move(b0)), a(*ownerA->atDetail(o.detailA).model),
        b(*ownerB->atDetail(o.detailB).model), options(resolve(a, b, o)),
        updater(a, b, options.tolerance, options.maxLocalIterations),
        mergeDistance(std::max(16 * options.tolerance, 1e-5 * std::min(boundedDiagonal(a), boundedDiagonal(b)))) {}

  bool passDue(const Eigen::Isometry3d& X_AB) const {
    return !passed || updatesSincePass >= options.globalPeriod ||
           relativeMotion(a, b, X_ABpass, X_AB) > options.guard;
  }

  void startPass(const Eigen::Isometry3d& X_AB, bool inlinePass) {
    passed = true;
    X_ABpass = X_AB;
    updatesSincePass = 0;
    ++counters.globalPasses;
    last.globalPassStarted = true;
    if (inlinePass) {
      merge(globalPass(a, b, updater, options, X_AB), X_AB);
      return;
    }
    // The worker reads the models (const, thread-safe) and the updater (const); its copies of the options and
    // the pose are its own. The models outlive it: the future's destructor waits.
    pending = std::async(std::launch::async, [this, X_AB] { return globalPass(a, b, updater, options, X_AB); });
  }

  /// A pass's minima, locally updated to the current pose, join the tracked ones (duplicates removed later).
  void merge(std::vector<LocalMinimum> found, const Eigen::Isometry3d& X_AB) {
    last.globalPassMerged = true;
    tracking::Work work;
    for (LocalMinimum& m : found) {
      if (!updater.update(m, X_AB, work)) continue;
      Track t;
      t.m = m;
      t.id = nextId++;
      t.age = -1;  // becomes 0 at the end of this update
      tracks.push_back(t);
      ++last.added;
    }
    account(work);
  }

  void account(const tracking::Work& w) {
    counters.newtonIterations += w.newton;
    counters.localSteps += w.steps;
    counters.fallbacks += w.fallbacks;
  }

  /// Oldest first; a minimum whose points both lie within the merge distance of a kept one's is the same.
  void dedupeAndDrop() {
    std::stable_sort(tracks.begin(), tracks.end(), [](const Track& x, const Track& y) { return x.age > y.age; });
    const double far = options.cutoff + 2 * options.guard;
    std::vector<Track> kept;
    for (Track& t : tracks) {
      if (!std::isfinite(t.m.distance) || t.m.distance > far) {
        if (t.age >= 0) ++last.dropped;
        else --last.added;
        continue;
      }
      const bool same = std::any_of(kept.begin(), kept.end(), [&](const Track& k) {
        return (k.m.pA_A - t.m.pA_A).norm() <= mergeDistance && (k.m.pB_B - t.m.pB_B).norm() <= mergeDistance;
      });
      if (same) {
        if (t.age >= 0) ++last.merged;
        else --last.added;
        continue;
      }
      kept.push_back(std::move(t));
    }
    tracks = std::move(kept);
  }

  void report(const Eigen::Isometry3d& X_WA, const Eigen::Isometry3d& X_WB, const Eigen::Isometry3d& X_AB) {
    minima.clear();
    std::vector<double> pushes;
    // A minimum followed continuously changes its distance by at most the pair's relative motion; a larger change
    // is a jump onto another branch (converging onto a neighbour, a facet's minimum passing to the next), whose
    // rate is no speed: damping it gave single-update force spikes of twice the contact force.
    const double motion = hasPreviousPose ? relativeMotion(a, b, previousX_AB, X_AB) : 0.0;
    previousX_AB = X_AB;
    hasPreviousPose = true;
    for (Track& t : tracks) {
      ++t.age;
      const double d = t.m.distance;
      const double change = t.hasPrevious ? d - t.previous : 0.0;
      const double rate = std::abs(change) <= motion + options.tolerance ? change / options.timeStep : 0.0;
      t.previous = d;
      t.hasPrevious = true;
      if (d > options.cutoff) continue;
      TrackedMinimum r;
      r.pointA = X_WA * t.m.pA_A;
      r.pointB = X_WB * t.m.pB_B;
      r.normal = X_WA.linear() * t.m.normal_A;
      r.distance = d;
      r.featureA = t.m.hintA.feature, r.featureB = t.m.hintB.feature;
      r.paramA = t.m.hintA.param, r.paramB = t.m.hintB.param;
      r.age = t.age;
      r.id = t.id;
      const double push = options.stiffness * (options.penaltyDistance - d) - options.damping * rate;
      pushes.push_back(d < options.penaltyDistance ? std::max(0.0, push) : 0.0);
      minima.push_back(r);
    }
    shareForces(pushes, X_WA * options.referencePoint_A);
    std::sort(minima.begin(), minima.end(), [](const TrackedMinimum& x, const TrackedMinimum& y) {
      return x.distance < y.distance;
    });
    last.minima = static_cast<int>(minima.size());
    last.deepest = minima.empty() ? std::numeric_limits<double>::infinity() : minima.front().distance;
  }

  /// Minima pushing the same way share one spring (tracker.h, "Forces"): minimum i gets push_i² / Σ_j w_ij push_j,
  /// w_ij = 1 for normals within 15°, 0 beyond 45°, smooth between — so a flat contact that a faceted surface splits
  /// into one, two or five minima pushes as one, and a minimum entering at zero push changes nothing.
  void shareForces(const std::vector<double>& pushes, const Eigen::Vector3d& ref_W) {
    const double lo = std::sqrt(0.5), hi = 0.96592582628906829;  // cos 45°, cos 15°
    for (std::size_t i = 0; i < minima.size(); ++i) {
      double shared = 0;
      for (std::size_t j = 0; j < minima.size(); ++j) {
        const double x = std::clamp((minima[i].normal.dot(minima[j].normal) - lo) / (hi - lo), 0.0, 1.0);
        shared += (i == j ? 1.0 : x * x * (3 - 2 * x)) * pushes[j];
      }
      TrackedMinimum& r = minima[i];
      r.force = shared > 0 ? pushes[i] * pushes[i] / shared : 0.0;
      const Eigen::Vector3d F = -r.force * r.normal;  // A is pushed away from B
      last.force += F;
      last.torque += (r.pointA - ref_W).cross(F);
    }
  }

  /// A local update reads its sign from the locally closest feature, which is right only for the globally
  /// closest one: a point above a slab whose walk ended on the slab's bottom face reads as the slab's thickness
  /// deep. A minimum that turns penetrating (or arrives so) must have a point inside the other solid (the models'
  /// own inside tests), else it is not a contact and is dropped. Once verified, a penetration that deepens
  /// continuously is not re-tested (that would cost a global point query per update).
  void dropFalseOverlaps(const Eigen::Isometry3d& X_AB) {
    const double tol = options.tolerance;
    const Eigen::Isometry3d X_BA = X_AB.inverse();
    for (Track& t : tracks) {
      const double d = t.m.distance;
      if (!(d < -tol) || (t.hasPrevious && t.previous < -tol)) continue;
      if (b.inside(X_BA * t.m.pA_A) || a.inside(X_AB * t.m.pB_B)) continue;
      t.m.distance = std::numeric_limits<double>::infinity();
      ++counters.falseOverlaps;
    }
  }

  void update(const Eigen::Isometry3d& X_WA, const Eigen::Isometry3d& X_WB) {
    if (!X_WA.matrix().allFinite() || !X_WB.matrix().allFinite()) throw InputError("Tracker: non-finite pose");
    last = TrackerUpdate{};
    ++counters.updates;
    ++updatesSincePass;
    const Eigen::Isometry3d X_AB = X_WA.inverse() * X_WB;
    tracking::Work work;
    for (Track& t : tracks)
      if (!updater.update(t.m, X_AB, work)) t.m.distance = std::numeric_limits<double>::infinity();
    account(work);
    if (pending.valid() && pending.wait_for(std::chrono::seconds(0)) == std::future_status::ready)
      merge(pending.get(), X_AB);
    if (passDue(X_AB) && !pending.valid())
      startPass(X_AB, options.globalPass == GlobalPassMode::Inline || !passed);
    dropFalseOverlaps(X_AB);
    dedupeAndDrop();
    report(X_WA, X_WB, X_AB);
  }
};

Tracker::Tracker(std::shared_ptr<const Model> a, std::shared_ptr<const Model> b, const TrackerOptions& options) {
  if (!a || !b) throw InputError("Tracker: missing model");
  if (a->type() == ModelType::Plane && b->type() == ModelType::Plane)
    throw InputError("plane-plane pairs are not supported");
  impl_ = std::make_unique<Impl>(std::move(a), std::move(b), options);
}

Tracker::~Tracker() {
  if (impl_ && impl_->pending.valid()) impl_->pending.wait();
}

const TrackerUpdate& Tracker::update(const Eigen::Isometry3d& X_WA, const Eigen::Isometry3d& X_WB) {
  impl_->update(X_WA, X_WB);
  return impl_->last;
}

const std::vector<TrackedMinimum>& Tracker::minima() const { return impl_->minima; }
const TrackerUpdate& Tracker::last() const { return impl_->last; }
const TrackerCounters& Tracker::counters() const { return impl_->counters; }
const TrackerOptions& Tracker::options() const { return impl_->options; }

void Tracker::waitForGlobalPass() {
  if (impl_->pending.valid()) impl_->pending.wait();
}

void Tracker::reset() {
  waitForGlobalPass();
  if (impl_->pending.valid()) impl_->pending.get();
  impl_->tracks.clear();
  impl_->minima.clear();
  impl_->passed = false;
  impl_->hasPreviousPose = false;
  impl_->last = TrackerUpdate{};
}

}  // namespace unidist
