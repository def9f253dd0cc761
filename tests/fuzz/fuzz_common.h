// Shared by the libFuzzer targets (tests/fuzz.sh, docs/reliability.md). The rule every target checks: an input
// either gives valid objects, whose answers are all finite, or throws unidist::InputError. Any other exception
// or a non-finite answer aborts, so libFuzzer records the input as a finding (as it does crashes, leaks, hangs
// and sanitizer reports).
#pragma once

#include "unidist/model.h"
#include "unidist/types.h"

#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>

namespace unidist::fuzz {

/// Inputs above this are skipped: the readers' cost grows with the size, and a bounded size keeps every
/// input's work (and so libFuzzer's per-input timeout) meaningful.
constexpr std::size_t kMaxInputBytes = 64 * 1024;

[[noreturn]] inline void finding(const std::string& what) {
  std::fprintf(stderr, "unidist fuzz finding: %s\n", what.c_str());
  std::abort();
}

inline void requireFinite(bool finite, const char* what) {
  if (!finite) finding(std::string("non-finite ") + what);
}

/// Runs f; an InputError is the accepted way to refuse an input, anything else is a finding.
template <class F>
void expectValidOrInputError(F&& f) {
  try {
    f();
  } catch (const InputError&) {
  } catch (const std::exception& e) {
    finding(std::string("exception other than InputError: ") + e.what());
  } catch (...) {
    finding("non-standard exception");
  }
}

/// A little of everything `unidist info` and a distance query ask of a model, all required finite.
inline void exerciseModel(const Model& model) {
  const Aabb box = model.localBounds();
  if (box.empty()) finding("empty bounds");
  if (model.type() != ModelType::Plane) {  // the one model unbounded by design
    if (!box.bounded()) finding("bounds not finite");
    const BoundingSphere ball = model.localBoundingSphere();
    requireFinite(ball.center.allFinite() && std::isfinite(ball.radius), "bounding sphere");
  }
  // A fixed point off any axis, so that degenerate closest points (centres, axes) are not the usual case.
  const SurfacePoint p = model.closestPoint(Eigen::Vector3d(0.31, -0.72, 1.13));
  requireFinite(p.point.allFinite() && p.normal.allFinite() && std::isfinite(p.signedDistance), "closest point");
  requireFinite(model.support(Eigen::Vector3d(0.6, 0.0, -0.8)).allFinite(), "support point");
  if (model.describe().empty()) finding("empty describe()");
  (void)model.memoryBytes();
}

/// The input written to one file per process (readers take paths), under TMPDIR so runs stay in the build tree.
class ScratchFile {
 public:
  explicit ScratchFile(const std::string& extension) {
    dir_ = std::filesystem::temp_directory_path() / ("unidist_fuzz_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
    path_ = (dir_ / ("input" + extension)).string();
  }
  ~ScratchFile() {
    std::error_code ignored;
    std::filesystem::remove_all(dir_, ignored);
  }
  const std::string& write(const std::uint8_t* data, std::size_t size) {
    std::ofstream out(path_, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!out) finding("cannot write the scratch file " + path_);
    return path_;
  }
  const std::filesystem::path& dir() const { return dir_; }

 private:
  std::filesystem::path dir_;
  std::string path_;
};

}  // namespace unidist::fuzz
