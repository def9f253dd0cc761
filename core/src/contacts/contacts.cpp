// The public contacts() entry: checks the input, turns boxes into exact meshes (so that a box gets corner
// contacts), picks the routine for the pair family (see unidist/contacts.h) and merges and reduces the result.
#include "unidist/contacts.h"

#include "contacts/point_contacts.h"
#include "contacts/reduce.h"
#include "contacts/rounding.h"
#include "contacts/snch.h"
#include "unidist/distance.h"
#include "unidist/primitives.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

namespace unidist {
namespace {

/// The model the contact routines work on: the model itself, or a box's mesh stand-in (so that a box gets
/// corner contacts).
struct Working {
  const Model* model;
  bool standIn;
  const TriangleMesh* mesh() const { return dynamic_cast<const TriangleMesh*>(model); }
};

Working working(const Model& m) {
  if (const auto* box = dynamic_cast<const Box*>(&m)) return {&box->asMesh(), true};
  return {&m, false};
}

Contact fromDistance(const DistanceResult& r) {
  Contact c;
  c.pointA = r.pointA, c.pointB = r.pointB, c.normal = r.normal, c.distance = r.distance;
  c.errorBound = r.errorBound();
  return c;
}

void toWorld(std::vector<Contact>& cs, const Eigen::Isometry3d& X_WA) {
  for (Contact& c : cs) {
    c.pointA = X_WA * c.pointA;
    c.pointB = X_WA * c.pointB;
    c.normal = X_WA.linear() * c.normal;
  }
}

/// Mesh–mesh: the normal cone search for separation and touching, the locally deepest vertices for overlap,
/// and the global answer when the meshes cross without a vertex inside the other.
void meshMesh(const TriangleMesh& a, const Eigen::Isometry3d& X_WA, const TriangleMesh& b,
              const Eigen::Isometry3d& X_WB, double margin, double tol, double dirEps, const Model& origA,
              const Model& origB, const DistanceOptions& global, std::vector<Contact>& out) {
  const contact::MeshFeatures fa(a), fb(b);
  const Eigen::Isometry3d X_AB = X_WA.inverse() * X_WB;
  contact::SnchResult r = contact::snchSearch(a, fa, b, fb, X_AB, margin, tol, dirEps);
  toWorld(r.contacts, X_WA);
  out.insert(out.end(), r.contacts.begin(), r.contacts.end());
  bool crossing = false;
  for (const auto& leaves : r.overlapping)
    if ((crossing = contact::leavesIntersect(a, b, X_AB, leaves[0], leaves[1]))) break;
  if (!crossing) {
    // Surfaces apart (or touching) but one solid wholly inside the other: no local search sees it (a vertex's
    // depth is not the way out); the global depth does.
    if (!out.empty()) return;
    const bool contained = (b.isSolid() && b.inside(X_AB.inverse() * a.vertices()[0])) ||
                           (a.isSolid() && a.inside(X_AB * b.vertices()[0]));
    if (!contained) return;
    const DistanceResult d = distance(origA, X_WA, origB, X_WB, global);
    if (d.distance < -tol) out.push_back(fromDistance(d));
    return;
  }
  // Crossing surfaces: the locally deepest vertices of each inside the other; when there are none (an edge
  // through an edge), the global penetration.
  const std::size_t before = out.size();
  contact::meshVertexContacts(a, fa, X_WA, b, X_WB, margin, tol, true, true, out);
  contact::meshVertexContacts(b, fb, X_WB, a, X_WA, margin, tol, false, true, out);
  if (out.size() > before) return;
  const DistanceResult d = distance(origA, X_WA, origB, X_WB, global);
  if (d.distance < -tol) out.push_back(fromDistance(d));
}

void pointQueries(const Working& w, const Eigen::Isometry3d& X_WM, const Model& other, const Eigen::Isometry3d& X_WO,
                  double margin, double tol, bool isA, std::vector<Contact>& out) {
  if (const TriangleMesh* m = w.mesh()) {
    const contact::MeshFeatures f(*m);
    contact::meshVertexContacts(*m, f, X_WM, other, X_WO, margin, tol, isA, false, out);
  } else if (const auto* c = dynamic_cast<const PointCloud*>(w.model)) {
    contact::cloudPointContacts(*c, X_WM, other, X_WO, margin, tol, isA, out);
  }
}


std::vector<Contact> contactsOfModels(const Model& a, const Eigen::Isometry3d& X_WA, const Model& b,
                                      const Eigen::Isometry3d& X_WB, const ContactOptions& options) {
  if (!std::isfinite(options.margin) || options.margin < 0)
    throw InputError("contacts: margin must be finite and >= 0");
  if (options.maxContacts < 0) throw InputError("contacts: maxContacts must be >= 0");
  if (std::isnan(options.tolerance) || options.tolerance == std::numeric_limits<double>::infinity())
    throw InputError("contacts: tolerance must be finite");
  if (!X_WA.matrix().allFinite() || !X_WB.matrix().allFinite()) throw InputError("contacts: non-finite pose");
  if (a.type() == ModelType::Plane && b.type() == ModelType::Plane)
    throw InputError("plane-plane pairs are not supported");

  const double defaultTol = defaultTolerance(a, X_WA, b, X_WB);
  // Never below 1e-12 × the size: rounding alone would otherwise turn "touching" into "apart".
  const double tol = options.tolerance >= 0 ? std::max(options.tolerance, 1e-3 * defaultTol) : defaultTol;
  const double dirEps = defaultTol;  // 1e-9 × size: below it the two points' direction is mostly rounding
  const double margin = options.margin;
  const Working wa = working(a), wb = working(b);
  // The global queries honour the caller's tolerance too: it is what makes contacts cheap enough per step.
  DistanceOptions global;
  static_cast<QueryOptions&>(global) = options;
  if (options.tolerance >= 0) global.tolerance = tol;

  std::vector<Contact> out;
  if (wa.mesh() && wb.mesh()) {
    meshMesh(*wa.mesh(), X_WA, *wb.mesh(), X_WB, margin, tol, dirEps, a, b, global, out);
  } else {
    pointQueries(wa, X_WA, b, X_WB, margin, tol, true, out);
    pointQueries(wb, X_WB, a, X_WA, margin, tol, false, out);
    const DistanceResult d = distance(a, X_WA, b, X_WB, global);
    if (d.distance <= margin + tol) {
      Contact c = fromDistance(d);
      c.featureA = a.closestPoint(X_WA.inverse() * c.pointA).feature;
      c.featureB = b.closestPoint(X_WB.inverse() * c.pointB).feature;
      out.push_back(c);
    }
  }
  // A box's contacts name the primitive's features, not its stand-in mesh's triangles.
  for (Contact& c : out) {
    if (wa.standIn) c.featureA = a.closestPoint(X_WA.inverse() * c.pointA).feature;
    if (wb.standIn) c.featureB = b.closestPoint(X_WB.inverse() * c.pointB).feature;
    c.errorBound += contact::roundingBound(c);
  }
  contact::mergeDuplicates(out, 16 * std::max(tol, dirEps));
  if (options.maxContacts > 0) contact::reduceContacts(out, options.maxContacts);
  return out;
}

}  // namespace

std::vector<Contact> contacts(const Model& a, const Eigen::Isometry3d& X_WA, const Model& b,
                              const Eigen::Isometry3d& X_WB, const ContactOptions& options) {
  if (const char* why = invalidDialSetting(options)) throw InputError(std::string("contacts: ") + why);
  // At a level of detail the contacts are the stand-ins' (their points, features and distances).
  ContactOptions exact = options;
  exact.detailA = exact.detailB = 0;
  const StandIn sa = a.atDetail(options.detailA), sb = b.atDetail(options.detailB);
  std::vector<Contact> out = contactsOfModels(*sa.model, X_WA, *sb.model, X_WB, exact);
  for (Contact& c : out) c.errorBound += sa.deviation + sb.deviation;
  return out;
}

}  // namespace unidist
