// One model file reader through loadModel, the format chosen by UNIDIST_FUZZ_EXTENSION (set per target in
// tests/fuzz/CMakeLists.txt: .obj, .stl, .ply, .xyz, .unurbs.json, .igs).
#include "fuzz_common.h"
#include "unidist/adapters/load.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace unidist::fuzz;
  if (size > kMaxInputBytes) return -1;  // -1: not added to the corpus
  static ScratchFile file(UNIDIST_FUZZ_EXTENSION);
  const std::string& path = file.write(data, size);
  expectValidOrInputError([&] { exerciseModel(*unidist::loadModel(path)); });
  return 0;
}
