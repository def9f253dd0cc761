// `unidist info A [--json] [--build]`: what a model is (type, description, bounds, solidity, convexity, memory,
// and the acceleration structures it builds lazily: whether each exists yet and its size).
#include "commands.h"
#include "output.h"

#include "unidist/adapters/load.h"
#include "unidist/nurbs.h"

namespace unidist::cli {

std::string runInfo(const InfoArgs& args) {
  std::shared_ptr<const Model> m;
  try {
    m = loadModel(args.model);
  } catch (const InputError& e) {
    throw InputError(std::string("A: ") + e.what());
  }
  if (args.build) m->buildStructures();
  const Aabb box = m->localBounds();
  std::string structuresJson, structuresText;
  for (const StructureReport& s : m->structures()) {
    structuresJson += std::string(structuresJson.empty() ? "" : ", ") + "{\"name\": " + jsonString(s.name) +
                      ", \"built\": " + (s.built ? "true" : "false") + ", \"bytes\": " + std::to_string(s.bytes) + "}";
    structuresText += std::string(structuresText.empty() ? "" : ", ") + s.name + " " +
                      (s.built ? std::to_string(s.bytes) + " bytes" : std::string("(built on first need)"));
  }
  const BoundingSphere ball = m->localBoundingSphere();
  const bool bounded = box.bounded();
  // A NURBS solid is convex when proved so (its support map is then a search, not a formula: isConvex() stays
  // false); the text says why not.
  bool convex = m->isConvex();
  std::string convexText = convex ? "yes" : "no";
  if (const auto* nurbs = dynamic_cast<const NurbsModel*>(m.get()); nurbs && nurbs->isSolid()) {
    std::string why;
    convex = nurbs->provedConvex(&why);
    convexText = convex ? "yes (proved: curvature and creases of every patch, one closed surface)" : "no: " + why;
  }

  std::string out;
  if (args.json) {
    out = "{\"type\": " + jsonString(toString(m->type())) + ", \"description\": " + jsonString(m->describe()) +
          ", \"bounded\": " + (bounded ? "true" : "false") + ", \"aabb\": {\"min\": " + jsonVector(box.min) +
          ", \"max\": " + jsonVector(box.max) + "}, \"bounding_sphere\": {\"center\": " + jsonVector(ball.center) +
          ", \"radius\": " + jsonNumber(ball.radius) + "}, \"solid\": " + (m->isSolid() ? "true" : "false") +
          ", \"convex\": " + (convex ? "true" : "false") +
          ", \"memory_bytes\": " + std::to_string(m->memoryBytes()) + ", \"structures\": [" + structuresJson + "]}\n";
  } else {
    out += "type         " + std::string(toString(m->type())) + "\n";
    out += "model        " + m->describe() + "\n";
    out += "aabb         min " + textVector(box.min) + "  max " + textVector(box.max) +
           (bounded ? "" : "  (unbounded)") + "\n";
    out += "bounding     centre " + textVector(ball.center) + "  radius " + textNumber(ball.radius) + "\n";
    out += "solid        " + std::string(m->isSolid() ? "yes" : "no (no inside: unsigned distances)") + "\n";
    out += "convex       " + convexText + "\n";
    out += "memory       " + std::to_string(m->memoryBytes()) + " bytes\n";
    if (!structuresText.empty()) out += "structures   " + structuresText + "\n";
  }
  return out;
}

}  // namespace unidist::cli
