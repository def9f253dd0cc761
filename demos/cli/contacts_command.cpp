// `unidist contacts A B [--pose-a P] [--pose-b P] [--margin M] [--max-contacts N] [--tol T] [--rel-tol R]
// [--max-iterations N] [--detail-a D] [--detail-b D] [--json]`: the local minimum distances within M
// (unidist/contacts.h, docs/contacts.md), in the conventions of docs/query-contract.md.
#include "commands.h"
#include "output.h"

#include "unidist/adapters/load.h"
#include "unidist/adapters/spec.h"
#include "unidist/contacts.h"

#include <cmath>
#include <stdexcept>

namespace unidist::cli {
namespace {

std::shared_ptr<const Model> loadAs(const std::string& specOrPath, const char* which) {
  try {
    return loadModel(specOrPath);
  } catch (const InputError& e) {
    throw InputError(std::string(which) + ": " + e.what());
  }
}

}  // namespace

std::string runContacts(const ContactsArgs& args) {
  ContactOptions options;
  applyDial(args.dial, options);
  if (args.hasMargin) {
    options.margin = parseNumber(args.margin, "--margin");
    if (options.margin < 0) throw InputError("--margin must be >= 0 (got " + textNumber(options.margin) + ")");
  }
  if (args.hasMaxContacts) {
    const double n = parseNumber(args.maxContacts, "--max-contacts");
    if (n < 0 || n != std::floor(n) || n > 1e9)
      throw InputError("--max-contacts must be a whole number >= 0 (got " + args.maxContacts + ")");
    options.maxContacts = static_cast<int>(n);
  }
  const Eigen::Isometry3d X_WA = args.hasPoseA ? parsePose(args.poseA, "--pose-a") : Eigen::Isometry3d::Identity();
  const Eigen::Isometry3d X_WB = args.hasPoseB ? parsePose(args.poseB, "--pose-b") : Eigen::Isometry3d::Identity();
  const std::shared_ptr<const Model> a = loadAs(args.a, "A");
  const std::shared_ptr<const Model> b = loadAs(args.b, "B");

  const std::vector<Contact> cs = contacts(*a, X_WA, *b, X_WB, options);
  for (const Contact& c : cs)
    if (!std::isfinite(c.distance) || !c.pointA.allFinite() || !c.pointB.allFinite() || !c.normal.allFinite())
      throw std::runtime_error("the contact search returned a non-finite contact");

  std::string out;
  if (args.json) {
    out = "{\"contacts\": [";
    for (std::size_t i = 0; i < cs.size(); ++i)
      out += std::string(i ? ", " : "") + "{\"point_a\": " + jsonVector(cs[i].pointA) +
             ", \"point_b\": " + jsonVector(cs[i].pointB) + ", \"normal\": " + jsonVector(cs[i].normal) +
             ", \"distance\": " + jsonNumber(cs[i].distance) + ", \"error_bound\": " + jsonNumber(cs[i].errorBound) + "}";
    out += "]}\n";
  } else {
    for (const Contact& c : cs)
      out += "distance " + textNumber(c.distance) + "  point_a " + textVector(c.pointA) + "  point_b " +
             textVector(c.pointB) + "  normal " + textVector(c.normal) + "  error_bound " + textNumber(c.errorBound) + "\n";
  }
  return out;
}

}  // namespace unidist::cli
