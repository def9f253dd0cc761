// What every primitive shares: constant memory, input validation and number formatting.
#include "unidist/primitives.h"

#include "primitives/common.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace unidist {

std::size_t Primitive::memoryBytes() const {
  switch (type()) {
    case ModelType::Sphere: return sizeof(Sphere);
    case ModelType::Box: return sizeof(Box);
    case ModelType::Capsule: return sizeof(Capsule);
    case ModelType::Cylinder: return sizeof(Cylinder);
    case ModelType::Cone: return sizeof(Cone);
    case ModelType::Torus: return sizeof(Torus);
    case ModelType::Plane: return sizeof(Plane);
    default: return sizeof(Primitive);
  }
}

namespace prim {

std::string formatNumber(double x) {
  char buf[40];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, x);
    // NaN never compares equal to its reading: the first attempt ("nan") is as good as any.
    if (std::isnan(x) || std::strtod(buf, nullptr) == x) break;
  }
  return buf;
}

void requireModelCoordinate(const Eigen::Vector3d& p, const char* what, std::size_t index) {
  const bool finite = p.allFinite();
  if (finite && p.cwiseAbs().maxCoeff() <= kMaxModelCoordinate) return;
  throw InputError(std::string(what) + " " + std::to_string(index) + (finite ? " has a coordinate beyond +-1e30 (" : " has a non-finite coordinate (") +
                   formatNumber(p.x()) + ", " + formatNumber(p.y()) + ", " + formatNumber(p.z()) +
                   (finite ? "); scale the model" : ")"));
}

std::string exact(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

void requirePositive(const char* shape, const char* field, double value) {
  if (std::isfinite(value) && value > 0) return;
  throw InputError(std::string(shape) + ": " + field + " must be finite and > 0 (got " + formatNumber(value) + ")");
}

}  // namespace prim
}  // namespace unidist
