// Primitive specs "name:key=value,...": one table of primitives with their keys and a builder each. The
// sizes are checked here, so that every message names the primitive and the key; the core constructors check
// again (they are the last word on what makes a valid primitive).
#include "unidist/adapters/spec.h"
#include "unidist/primitives.h"

#include "extent_check.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>

namespace unidist {
namespace {

constexpr std::size_t kMaxKeys = 4;

/// Values of one spec, in the order of the primitive's keys.
using Values = std::array<double, kMaxKeys>;

struct PrimitiveKind {
  const char* name;
  std::array<const char*, kMaxKeys> keys;  ///< unused slots are null
  std::shared_ptr<const Model> (*build)(const std::string& name, const Values& v);
};

std::string formatNumber(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

void requirePositive(const std::string& name, const char* key, double v) {
  if (!(v > 0)) throw InputError(name + ": " + key + " must be > 0 (got " + formatNumber(v) + ")");
}

const PrimitiveKind kKinds[] = {
    {"sphere", {"r"},
     [](const std::string& n, const Values& v) -> std::shared_ptr<const Model> {
       requirePositive(n, "r", v[0]);
       return std::make_shared<Sphere>(v[0]);
     }},
    {"box", {"hx", "hy", "hz"},
     [](const std::string& n, const Values& v) -> std::shared_ptr<const Model> {
       requirePositive(n, "hx", v[0]);
       requirePositive(n, "hy", v[1]);
       requirePositive(n, "hz", v[2]);
       return std::make_shared<Box>(Eigen::Vector3d(v[0], v[1], v[2]));
     }},
    {"capsule", {"r", "h"},
     [](const std::string& n, const Values& v) -> std::shared_ptr<const Model> {
       requirePositive(n, "r", v[0]);
       requirePositive(n, "h", v[1]);
       return std::make_shared<Capsule>(v[0], v[1]);
     }},
    {"cylinder", {"r", "h"},
     [](const std::string& n, const Values& v) -> std::shared_ptr<const Model> {
       requirePositive(n, "r", v[0]);
       requirePositive(n, "h", v[1]);
       return std::make_shared<Cylinder>(v[0], v[1]);
     }},
    {"cone", {"r", "h"},
     [](const std::string& n, const Values& v) -> std::shared_ptr<const Model> {
       requirePositive(n, "r", v[0]);
       requirePositive(n, "h", v[1]);
       return std::make_shared<Cone>(v[0], v[1]);
     }},
    {"torus", {"R", "r"},
     [](const std::string& n, const Values& v) -> std::shared_ptr<const Model> {
       requirePositive(n, "R", v[0]);
       requirePositive(n, "r", v[1]);
       if (!(v[1] < v[0]))
         throw InputError(n + ": r must be < R (got R=" + formatNumber(v[0]) + ", r=" + formatNumber(v[1]) + ")");
       return std::make_shared<Torus>(v[0], v[1]);
     }},
    {"plane", {"nx", "ny", "nz", "d"},
     [](const std::string& n, const Values& v) -> std::shared_ptr<const Model> {
       const Eigen::Vector3d normal(v[0], v[1], v[2]);
       // Scale before the norm so that tiny or huge components neither underflow to 0 nor overflow to Inf.
       const double m = normal.cwiseAbs().maxCoeff();
       if (!(m > 0)) throw InputError(n + ": normal (nx, ny, nz) must not be zero");
       const double len = m * (normal / m).norm();
       const double offset = v[3] / len;
       if (!std::isfinite(offset)) throw InputError(n + ": d / |n| is out of range (d=" + formatNumber(v[3]) + ")");
       // Handing the core a unit normal (same half-space) keeps |n| from overflowing there.
       return std::make_shared<Plane>((normal / m).normalized(), offset);
     }},
};

std::string keyList(const PrimitiveKind& kind) {
  std::string out;
  for (const char* k : kind.keys) {
    if (!k) break;
    if (!out.empty()) out += ",";
    out += k;
  }
  return out;
}

std::string kindList() {
  std::string out;
  for (const PrimitiveKind& k : kKinds) {
    if (!out.empty()) out += ", ";
    out += k.name;
  }
  return out;
}

}  // namespace

bool looksLikePrimitiveSpec(std::string_view text) {
  const std::size_t colon = text.find(':');
  if (colon == std::string_view::npos || colon == 0) return false;
  return std::all_of(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(colon),
                     [](char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0; });
}

std::shared_ptr<const Model> parsePrimitiveSpec(const std::string& spec) {
  if (!looksLikePrimitiveSpec(spec))
    throw InputError("'" + spec + "' is not a primitive spec (expected name:key=value,...)");
  const std::size_t colon = spec.find(':');
  const std::string name = spec.substr(0, colon);
  const PrimitiveKind* kind = nullptr;
  for (const PrimitiveKind& k : kKinds)
    if (name == k.name) kind = &k;
  if (!kind) throw InputError("unknown primitive '" + name + "' (known: " + kindList() + ")");

  Values values{};
  std::array<bool, kMaxKeys> seen{};
  const std::string body = spec.substr(colon + 1);
  if (!body.empty()) {
    std::size_t start = 0;
    while (true) {
      const std::size_t comma = body.find(',', start);
      const std::string item = body.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
      if (item.empty()) throw InputError(name + ": empty item in '" + body + "' (expected key=value,...)");
      const std::size_t eq = item.find('=');
      if (eq == std::string::npos) throw InputError(name + ": expected key=value, got '" + item + "'");
      const std::string key = item.substr(0, eq);
      std::size_t slot = kMaxKeys;
      for (std::size_t i = 0; i < kMaxKeys && kind->keys[i]; ++i)
        if (key == kind->keys[i]) slot = i;
      if (slot == kMaxKeys)
        throw InputError(name + ": unknown key '" + key + "' (expected " + keyList(*kind) + ")");
      if (seen[slot]) throw InputError(name + ": duplicate key '" + key + "'");
      seen[slot] = true;
      values[slot] = parseNumber(std::string_view(item).substr(eq + 1), name + ": " + key);
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
  }
  for (std::size_t i = 0; i < kMaxKeys && kind->keys[i]; ++i)
    if (!seen[i]) throw InputError(name + ": missing key '" + kind->keys[i] + "'");
  std::shared_ptr<const Model> model = kind->build(name, values);
  requireFiniteExtent(*model, name);
  return model;
}

}  // namespace unidist
