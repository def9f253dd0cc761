// Scene JSON (parseScene): every body valid and its model exercised. Relative model paths resolve in an empty
// scratch directory, so file models fail as missing files; the readers have their own targets.
#include "fuzz_common.h"
#include "unidist/adapters/scene.h"

#include <cmath>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace unidist::fuzz;
  if (size > kMaxInputBytes) return -1;
  static ScratchFile scratch(".json");
  const std::string text(reinterpret_cast<const char*>(data), size);
  expectValidOrInputError([&] {
    const unidist::Scene scene = unidist::parseScene(text, scratch.dir().string(), "fuzz.json");
    requireFinite(scene.gravity.allFinite() && std::isfinite(scene.dt), "scene gravity or dt");
    if (!(scene.dt > 0) || scene.steps < 0 || scene.bodies.empty()) finding("scene dt, steps or bodies invalid");
    for (const unidist::SceneBody& body : scene.bodies) {
      if (!body.model) finding("body without a model");
      requireFinite(body.pose.matrix().allFinite() && body.linearVelocity.allFinite() &&
                        body.angularVelocity.allFinite() && std::isfinite(body.mass) &&
                        std::isfinite(body.friction) && std::isfinite(body.restitution),
                    "body value");
      exerciseModel(*body.model);
    }
  });
  return 0;
}
