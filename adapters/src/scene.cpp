// Scene files (unidist/adapters/scene.h): strict JSON, every problem named with the scene and the JSON path of
// the value ("scene.json: bodies[1] (\"ball\"): mass: must be > 0 for a dynamic body").
#include "unidist/adapters/scene.h"

#include "formats/text_scanner.h"
#include "unidist/adapters/load.h"
#include "unidist/adapters/spec.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <map>
#include <set>

namespace unidist {
namespace {

using nlohmann::json;

class SceneParser {
 public:
  SceneParser(std::string baseDir, std::string what) : baseDir_(std::move(baseDir)), what_(std::move(what)) {}

  Scene parse(const std::string& text) {
    json root;
    try {
      root = json::parse(text);
    } catch (const json::exception& e) {
      throw InputError(what_ + ": not valid JSON (" + shortReason(e.what()) + ")");
    }
    onlyKeys(root, "top level", {"gravity", "dt", "steps", "bodies"}, {"bodies"});
    Scene s;
    s.path = what_;
    if (root.contains("gravity")) s.gravity = vector3(root["gravity"], "gravity");
    if (root.contains("dt")) s.dt = positive(root["dt"], "dt");
    if (root.contains("steps")) s.steps = count(root["steps"], "steps");
    const json& bodies = root["bodies"];
    if (!bodies.is_array() || bodies.empty()) fail("bodies", "must be a non-empty array of bodies");
    std::set<std::string> names;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      s.bodies.push_back(body(bodies[i], "bodies[" + std::to_string(i) + "]"));
      if (!names.insert(s.bodies.back().name).second)
        fail("bodies[" + std::to_string(i) + "]", "duplicate body name \"" + s.bodies.back().name + "\"");
    }
    return s;
  }

 private:
  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw InputError(what_ + ": " + where + ": " + what);
  }

  static std::string shortReason(const std::string& what) {
    const auto colon = what.rfind(": ");
    return colon == std::string::npos ? what : what.substr(colon + 2);
  }

  void onlyKeys(const json& object, const std::string& where, std::initializer_list<const char*> allowed,
                std::initializer_list<const char*> required) const {
    if (!object.is_object()) fail(where, "must be a JSON object");
    for (const char* k : required)
      if (!object.contains(k)) fail(where, std::string("missing key \"") + k + "\"");
    std::set<std::string> known(allowed.begin(), allowed.end());
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

  int count(const json& v, const std::string& where) const {
    if (!v.is_number_integer() || v.get<long long>() < 0 || v.get<long long>() > 100000000)
      fail(where, "must be an integer in [0, 1e8] (got " + v.dump() + ")");
    return static_cast<int>(v.get<long long>());
  }

  Eigen::Vector3d vector3(const json& v, const std::string& where) const {
    if (!v.is_array() || v.size() != 3) fail(where, "must be an array of 3 numbers");
    return {number(v[0], where + "[0]"), number(v[1], where + "[1]"), number(v[2], where + "[2]")};
  }

  Eigen::Isometry3d pose(const json& v, const std::string& where) const {
    if (!v.is_array() || v.size() != 7) fail(where, "must be an array of 7 numbers [tx,ty,tz,qw,qx,qy,qz]");
    double x[7];
    for (int i = 0; i < 7; ++i) x[i] = number(v[i], where + "[" + std::to_string(i) + "]");
    Eigen::Quaterniond q(x[3], x[4], x[5], x[6]);
    if (q.norm() < 1e-12) fail(where, "the quaternion is zero");
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() = q.normalized().toRotationMatrix();
    X.translation() = Eigen::Vector3d(x[0], x[1], x[2]);
    return X;
  }

  /// One model per distinct source text: bodies naming the same file share it (and its hierarchy).
  std::shared_ptr<const Model> model(const std::string& source, const std::string& where) {
    auto found = models_.find(source);
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

  SceneBody body(const json& v, const std::string& index) {
    // Name the body in every message once its name can be read.
    const bool named = v.is_object() && v.contains("name") && v["name"].is_string();
    const std::string at = named ? index + " (\"" + v["name"].get<std::string>() + "\")" : index;
    onlyKeys(v, at,
             {"name", "model", "pose", "static", "mass", "friction", "restitution", "tolerance", "linear_velocity",
              "angular_velocity"},
             {"name", "model"});
    if (!v["name"].is_string() || v["name"].get<std::string>().empty()) fail(at + ".name", "must be a non-empty string");
    SceneBody b;
    b.name = v["name"].get<std::string>();
    const std::string& where = at;
    if (!v["model"].is_string()) fail(where + ".model", "must be a string (a model file or a primitive spec)");
    b.modelSource = v["model"].get<std::string>();
    b.model = model(b.modelSource, where + ".model");
    if (v.contains("static")) {
      if (!v["static"].is_boolean()) fail(where + ".static", "must be true or false");
      b.isStatic = v["static"].get<bool>();
    }
    if (v.contains("pose")) b.pose = pose(v["pose"], where + ".pose");
    if (b.isStatic) {
      if (v.contains("mass")) fail(where + ".mass", "a static body has no mass");
    } else {
      if (!v.contains("mass")) fail(where, "missing key \"mass\" (required for a dynamic body)");
      b.mass = positive(v["mass"], where + ".mass");
      if (!b.model->localBounds().bounded()) fail(where, "an unbounded model (" + b.modelSource + ") must be static");
    }
    if (v.contains("friction")) b.friction = nonNegative(v["friction"], where + ".friction");
    if (v.contains("restitution")) {
      b.restitution = nonNegative(v["restitution"], where + ".restitution");
      if (b.restitution > 1) fail(where + ".restitution", "must be in [0, 1]");
    }
    if (v.contains("tolerance")) b.tolerance = positive(v["tolerance"], where + ".tolerance");
    if (v.contains("linear_velocity")) b.linearVelocity = vector3(v["linear_velocity"], where + ".linear_velocity");
    if (v.contains("angular_velocity")) b.angularVelocity = vector3(v["angular_velocity"], where + ".angular_velocity");
    return b;
  }

  std::string baseDir_, what_;
  std::map<std::string, std::shared_ptr<const Model>> models_;
};

}  // namespace

Scene parseScene(const std::string& jsonText, const std::string& baseDir, const std::string& what) {
  return SceneParser(baseDir, what).parse(jsonText);
}

Scene loadScene(const std::string& path) {
  const std::string text = formats::readWholeFile(path);
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return parseScene(text, dir.empty() ? "." : dir, path);
}

}  // namespace unidist
