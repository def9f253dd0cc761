// Primitive specs (parsePrimitiveSpec), with loadModel's spec-or-path decision on the same text.
#include "fuzz_common.h"
#include "unidist/adapters/spec.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace unidist::fuzz;
  if (size > 4096) return -1;  // a spec is one command-line word
  const std::string text(reinterpret_cast<const char*>(data), size);
  (void)unidist::looksLikePrimitiveSpec(text);
  expectValidOrInputError([&] { exerciseModel(*unidist::parsePrimitiveSpec(text)); });
  return 0;
}
