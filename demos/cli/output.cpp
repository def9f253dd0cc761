#include "output.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>

namespace unidist::cli {

std::string textNumber(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string jsonNumber(double v) { return std::isfinite(v) ? textNumber(v) : "null"; }

std::string jsonVector(const Eigen::Vector3d& v) {
  return "[" + jsonNumber(v.x()) + "," + jsonNumber(v.y()) + "," + jsonNumber(v.z()) + "]";
}

std::string jsonString(const std::string& s) {
  // Invalid UTF-8 (a file name, say) is replaced rather than thrown about: the output stays valid JSON.
  return nlohmann::json(s).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::string textVector(const Eigen::Vector3d& v) {
  return textNumber(v.x()) + " " + textNumber(v.y()) + " " + textNumber(v.z());
}

}  // namespace unidist::cli
