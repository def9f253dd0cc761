// Haptic scene files (haptic_scene.h): strict JSON, every problem named with the file and the JSON path of the
// value ("haptic.json: probes[0] (\"ball\").waypoints[2][1]: must be finite").
#include "haptic_scene.h"

#include "unidist/adapters/load.h"
#include "unidist/adapters/spec.h"
#include "unidist/types.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace unidist::haptic {
namespace {

using nlohmann::json;

class HapticSceneParser {
 public:
  HapticSceneParser(std::string baseDir, std::string what) : baseDir_(std::move(baseDir)), what_(std::move(what)) {}

  HapticScene parse(const std::string& text) {
    json root;
    try {
      root = json::parse(text);
    } catch (const json::exception& e) {
      throw InputError(what_ + ": not valid JSON (" + std::string(e.what()) + ")");
    }
    onlyKeys(root, "top level", {"servo_rate_hz", "steps", "tracker", "environment", "probes"},
             {"steps", "tracker", "environment", "probes"});
    HapticScene s;
    s.path = what_;
    if (root.contains("servo_rate_hz")) s.servoRateHz = positive(root["servo_rate_hz"], "servo_rate_hz");
    s.steps = wholeNumber(root["steps"], "steps", 2);
    tracker(root["tracker"], s);
    s.environment = namedList<EnvironmentModel>(root, "environment", [&](const json& v, const std::string& at) {
      onlyKeys(v, at, {"name", "model", "pose"}, {"name", "model"});
      EnvironmentModel e;
      e.model = model(v["model"], at + ".model");
      if (v.contains("pose")) e.pose = pose(v["pose"], at + ".pose");
      return e;
    });
    s.probes = namedList<Probe>(root, "probes", [&](const json& v, const std::string& at) {
      onlyKeys(v, at, {"name", "model", "waypoints"}, {"name", "model", "waypoints"});
      Probe p;
      p.model = model(v["model"], at + ".model");
      const json& w = v["waypoints"];
      if (!w.is_array() || w.size() < 2) fail(at + ".waypoints", "must be an array of at least 2 poses");
      for (std::size_t i = 0; i < w.size(); ++i) p.waypoints.push_back(pose(w[i], at + ".waypoints[" + index(i) + "]"));
      return p;
    });
    for (const Probe& p : s.probes)
      if (!p.model->localBounds().bounded()) fail("probes", "a probe must be bounded (\"" + p.name + "\" is not)");
    return s;
  }

 private:
  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw InputError(what_ + ": " + where + ": " + what);
  }

  static std::string index(std::size_t i) { return std::to_string(i); }

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

  int wholeNumber(const json& v, const std::string& where, int min) const {
    if (!v.is_number_integer() || v.get<long long>() < min || v.get<long long>() > 100000000)
      fail(where, "must be an integer in [" + std::to_string(min) + ", 1e8] (got " + v.dump() + ")");
    return static_cast<int>(v.get<long long>());
  }

  Eigen::Isometry3d pose(const json& v, const std::string& where) const {
    if (!v.is_array() || v.size() != 7) fail(where, "must be an array of 7 numbers [tx,ty,tz,qw,qx,qy,qz]");
    double x[7];
    for (std::size_t i = 0; i < 7; ++i) x[i] = number(v[i], where + "[" + index(i) + "]");
    const Eigen::Quaterniond q(x[3], x[4], x[5], x[6]);
    if (q.norm() < 1e-12) fail(where, "the quaternion is zero");
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() = q.normalized().toRotationMatrix();
    X.translation() = Eigen::Vector3d(x[0], x[1], x[2]);
    return X;
  }

  void tracker(const json& v, HapticScene& s) const {
    onlyKeys(v, "tracker",
             {"cutoff", "stiffness", "damping", "penalty_distance", "guard", "global_period", "global_pass",
              "miss_tolerance"},
             {"cutoff", "stiffness"});
    TrackerOptions& o = s.tracker;
    o.cutoff = positive(v["cutoff"], "tracker.cutoff");
    o.stiffness = nonNegative(v["stiffness"], "tracker.stiffness");
    if (v.contains("damping")) o.damping = nonNegative(v["damping"], "tracker.damping");
    if (v.contains("penalty_distance")) {
      o.penaltyDistance = nonNegative(v["penalty_distance"], "tracker.penalty_distance");
      if (o.penaltyDistance > o.cutoff) fail("tracker.penalty_distance", "must be <= cutoff");
    }
    if (v.contains("guard")) o.guard = positive(v["guard"], "tracker.guard");
    if (v.contains("global_period")) o.globalPeriod = wholeNumber(v["global_period"], "tracker.global_period", 1);
    if (v.contains("global_pass")) {
      const json& m = v["global_pass"];
      if (m == "inline") o.globalPass = GlobalPassMode::Inline;
      else if (m == "background") o.globalPass = GlobalPassMode::Background;
      else fail("tracker.global_pass", "must be \"inline\" or \"background\" (got " + m.dump() + ")");
    }
    if (v.contains("miss_tolerance")) s.missTolerance = positive(v["miss_tolerance"], "tracker.miss_tolerance");
    o.timeStep = 1 / s.servoRateHz;
  }

  /// A non-empty array of objects with unique non-empty "name"s; `item` reads the rest of each.
  template <class T, class Item>
  std::vector<T> namedList(const json& root, const char* key, Item item) const {
    const json& list = root[key];
    if (!list.is_array() || list.empty()) fail(key, "must be a non-empty array");
    std::vector<T> out;
    std::set<std::string> names;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const json& v = list[i];
      std::string at = std::string(key) + "[" + index(i) + "]";
      if (v.is_object() && v.contains("name")) {
        if (!v["name"].is_string() || v["name"].get<std::string>().empty())
          fail(at + ".name", "must be a non-empty string");
        at += " (\"" + v["name"].get<std::string>() + "\")";
      }
      T t = item(v, at);
      t.name = v["name"].get<std::string>();
      if (!names.insert(t.name).second) fail(at, "duplicate name");
      out.push_back(std::move(t));
    }
    return out;
  }

  /// One model per distinct text (a probe and an environment model may share it).
  std::shared_ptr<const Model> model(const json& v, const std::string& where) const {
    if (!v.is_string()) fail(where, "must be a string (a model file or a primitive spec)");
    const std::string source = v.get<std::string>();
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

  std::string baseDir_, what_;
  mutable std::map<std::string, std::shared_ptr<const Model>> models_;
};

}  // namespace

HapticScene parseHapticScene(const std::string& jsonText, const std::string& baseDir, const std::string& what) {
  return HapticSceneParser(baseDir, what).parse(jsonText);
}

HapticScene loadHapticScene(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the haptic scene");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(path + ": cannot read the haptic scene");
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return parseHapticScene(text.str(), dir.empty() ? "." : dir, path);
}

}  // namespace unidist::haptic
