// `unidist sim --render DIR`: one PNG picture per recorded step, DIR/frame_00000.png, frame_00001.png, ...
// (frame 0 is the start; then every K-th step and the last). Built only with the renderer (UNIDIST_HAVE_RENDER).
#pragma once

#include "unidist/adapters/scene.h"

#include <memory>
#include <string>

namespace unidist::render {
class SceneRenderer;
}

namespace unidist::cli {

class SimFrames {
 public:
  /// Creates DIR (and its parents) when missing and sets up the renderer; throws InputError when DIR cannot be
  /// made or is not a directory.
  SimFrames(const Scene& scene, const std::string& dir, int width, int height);
  ~SimFrames();
  SimFrames(const SimFrames&) = delete;
  SimFrames& operator=(const SimFrames&) = delete;

  /// Renders and writes the next frame; throws InputError when the file cannot be written.
  void write(const std::vector<BodyState>& bodies, const std::vector<SimContact>& contacts);
  int written() const { return written_; }
  /// Wall-clock seconds spent rendering and writing, over all frames.
  double seconds() const { return seconds_; }

 private:
  std::unique_ptr<render::SceneRenderer> renderer_;
  std::string dir_;
  int written_ = 0;
  double seconds_ = 0;
};

}  // namespace unidist::cli
