#include "sim_frames.h"

#include "unidist/render/scene_renderer.h"

#include <chrono>
#include <cstdio>
#include <filesystem>

namespace unidist::cli {

SimFrames::SimFrames(const Scene& scene, const std::string& dir, int width, int height) : dir_(dir) {
  std::error_code error;
  if (std::filesystem::exists(dir, error) && !std::filesystem::is_directory(dir, error))
    throw InputError(dir + ": --render needs a directory, not a file");
  std::filesystem::create_directories(dir, error);
  if (error) throw InputError(dir + ": cannot create the frame directory (" + error.message() + ")");
  render::RenderOptions options;
  options.width = width;
  options.height = height;
  renderer_ = std::make_unique<render::SceneRenderer>(scene, options);
}

SimFrames::~SimFrames() = default;

void SimFrames::write(const std::vector<BodyState>& bodies, const std::vector<SimContact>& contacts) {
  const auto start = std::chrono::steady_clock::now();
  char name[32];
  std::snprintf(name, sizeof name, "frame_%05d.png", written_);
  render::writePng((std::filesystem::path(dir_) / name).string(), renderer_->render(bodies, contacts));
  ++written_;
  seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace unidist::cli
