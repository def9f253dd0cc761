// Strict JSON reading shared by the JSON formats (scene.cpp, haptic_scene.cpp, formats/unurbs_reader.cpp): every problem throws InputError
// naming the source and the JSON path of the value ("scene.json: bodies[1] (\"ball\").mass: must be > 0").
// Models are loaded once per distinct text (bodies naming the same file share one model and its hierarchy).
// Internal.
#pragma once

#include "unidist/adapters/load.h"
#include "unidist/adapters/spec.h"
#include "unidist/types.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <map>
#include <memory>
#include <set>
#include <string>

namespace unidist {

class JsonFields {
 public:
  using json = nlohmann::json;

  /// `baseDir` resolves relative model paths; `what` names the source in messages.
  JsonFields(std::string baseDir, std::string what) : baseDir_(std::move(baseDir)), what_(std::move(what)) {}

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw InputError(what_ + ": " + where + ": " + what);
  }

  /// nlohmann's message without its "[json.exception...] parse error at line 1, column 2: " prefix.
  static std::string shortReason(const std::string& what) {
    const auto colon = what.rfind(": ");
    return colon == std::string::npos ? what : what.substr(colon + 2);
  }

  /// The whole text as JSON, or InputError "<source>: not valid JSON (<reason>)".
  json parseDocument(const std::string& text) const {
    try {
      return json::parse(text);
    } catch (const json::exception& e) {
      throw InputError(what_ + ": not valid JSON (" + shortReason(e.what()) + ")");
    }
  }

  /// The object has every required key and no key outside `allowed`.
  void onlyKeys(const json& object, const std::string& where, std::initializer_list<const char*> allowed,
                std::initializer_list<const char*> required) const {
    if (!object.is_object()) fail(where, "must be a JSON object");
    for (const char* k : required)
      if (!object.contains(k)) fail(where, std::string("missing key \"") + k + "\"");
    const std::set<std::string> known(allowed.begin(), allowed.end());
    for (const auto& item : object.items())
      if (!known.count(item.key())) fail(where, "unknown key \"" + item.key() + "\"");
  }

  double number(const json& v, const std::string& where) const {
    if (!v.is_number()) fail(where, "must be a number");
    const double x = v.get<double>();
    if (!std::isfinite(x)) fail(where, "must be finite");
    return x;
  }

  double positive(const json& v, const std::string& where) const {
    const double x = number(v, where);
    if (x <= 0) fail(where, "must be > 0 (got " + v.dump() + ")");
    return x;
  }

  double nonNegative(const json& v, const std::string& where) const {
    const double x = number(v, where);
    if (x < 0) fail(where, "must be >= 0 (got " + v.dump() + ")");
    return x;
  }

  /// An integer in [min, 1e8].
  int integer(const json& v, const std::string& where, int min) const {
    if (!v.is_number_integer() || v.get<long long>() < min || v.get<long long>() > 100000000)
      fail(where, "must be an integer in [" + std::to_string(min) + ", 1e8] (got " + v.dump() + ")");
    return static_cast<int>(v.get<long long>());
  }

  Eigen::Vector3d vector3(const json& v, const std::string& where) const {
    if (!v.is_array() || v.size() != 3) fail(where, "must be an array of 3 numbers");
    return {number(v[0], where + "[0]"), number(v[1], where + "[1]"), number(v[2], where + "[2]")};
  }

  /// [tx, ty, tz, qw, qx, qy, qz], the quaternion normalised.
  Eigen::Isometry3d pose(const json& v, const std::string& where) const {
    if (!v.is_array() || v.size() != 7) fail(where, "must be an array of 7 numbers [tx,ty,tz,qw,qx,qy,qz]");
    double x[7];
    for (int i = 0; i < 7; ++i) x[i] = number(v[i], where + "[" + std::to_string(i) + "]");
    const Eigen::Quaterniond q(x[3], x[4], x[5], x[6]);
    if (q.norm() < 1e-12) fail(where, "the quaternion is zero");
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() = q.normalized().toRotationMatrix();
    X.translation() = Eigen::Vector3d(x[0], x[1], x[2]);
    return X;
  }

  /// A primitive spec or a model file (relative to baseDir), loaded once per distinct text.
  std::shared_ptr<const Model> model(const std::string& source, const std::string& where) {
    const auto found = models_.find(source);
    if (found != models_.end()) return found->second;
    std::string resolved = source;
    if (!looksLikePrimitiveSpec(source) && std::filesystem::path(source).is_relative())
      resolved = (std::filesystem::path(baseDir_) / source).lexically_normal().string();
    try {
      return models_[source] = loadModel(resolved);
    } catch (const InputError& e) {
      fail(where, e.what());
    }
  }

  const std::string& what() const { return what_; }

 private:
  std::string baseDir_, what_;
  std::map<std::string, std::shared_ptr<const Model>> models_;
};

}  // namespace unidist
