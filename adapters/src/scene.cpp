// Scene files (unidist/adapters/scene.h): strict JSON, every problem named with the scene and the JSON path of
// the value ("scene.json: bodies[1] (\"ball\"): mass: must be > 0 for a dynamic body").
#include "unidist/adapters/scene.h"

#include "formats/text_scanner.h"
#include "json_fields.h"

#include <filesystem>
#include <set>

namespace unidist {
namespace {

using json = JsonFields::json;

class SceneParser : JsonFields {
 public:
  using JsonFields::JsonFields;

  Scene parse(const std::string& text) {
    json root = parseDocument(text);
    onlyKeys(root, "top level", {"gravity", "dt", "steps", "bodies"}, {"bodies"});
    Scene s;
    s.path = what();
    if (root.contains("gravity")) s.gravity = vector3(root["gravity"], "gravity");
    if (root.contains("dt")) s.dt = positive(root["dt"], "dt");
    if (root.contains("steps")) s.steps = integer(root["steps"], "steps", 0);
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
