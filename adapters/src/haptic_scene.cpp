// Haptic scene files (unidist/adapters/haptic_scene.h): strict JSON, every problem named with the file and the JSON path of the
// value ("haptic.json: probes[0] (\"ball\").waypoints[2][1]: must be finite").
#include "unidist/adapters/haptic_scene.h"

#include "formats/text_scanner.h"
#include "json_fields.h"

#include <filesystem>
#include <set>

namespace unidist::haptic {
namespace {

using json = JsonFields::json;

class HapticSceneParser : JsonFields {
 public:
  using JsonFields::JsonFields;

  HapticScene parse(const std::string& text) {
    json root = parseDocument(text);
    onlyKeys(root, "top level", {"servo_rate_hz", "steps", "tracker", "environment", "probes"},
             {"steps", "tracker", "environment", "probes"});
    HapticScene s;
    s.path = what();
    if (root.contains("servo_rate_hz")) s.servoRateHz = positive(root["servo_rate_hz"], "servo_rate_hz");
    s.steps = integer(root["steps"], "steps", 2);
    tracker(root["tracker"], s);
    s.environment = namedList<EnvironmentModel>(root, "environment", [&](const json& v, const std::string& at) {
      onlyKeys(v, at, {"name", "model", "pose"}, {"name", "model"});
      EnvironmentModel e;
      e.model = modelOf(v["model"], at + ".model");
      if (v.contains("pose")) e.pose = pose(v["pose"], at + ".pose");
      return e;
    });
    s.probes = namedList<Probe>(root, "probes", [&](const json& v, const std::string& at) {
      onlyKeys(v, at, {"name", "model", "waypoints"}, {"name", "model", "waypoints"});
      Probe p;
      p.model = modelOf(v["model"], at + ".model");
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
  static std::string index(std::size_t i) { return std::to_string(i); }

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
    if (v.contains("global_period")) o.globalPeriod = integer(v["global_period"], "tracker.global_period", 1);
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

  /// A model text (spec or file); a probe and an environment model naming the same text share one model.
  std::shared_ptr<const Model> modelOf(const json& v, const std::string& where) {
    if (!v.is_string()) fail(where, "must be a string (a model file or a primitive spec)");
    return model(v.get<std::string>(), where);
  }
};

}  // namespace

HapticScene parseHapticScene(const std::string& jsonText, const std::string& baseDir, const std::string& what) {
  return HapticSceneParser(baseDir, what).parse(jsonText);
}

HapticScene loadHapticScene(const std::string& path) {
  const std::string text = formats::readWholeFile(path);
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return parseHapticScene(text, dir.empty() ? "." : dir, path);
}

}  // namespace unidist::haptic
