// Headless pictures of a scene (OSMesa through unidist::raster's OffscreenContext): every body's display
// tessellation (built once, in the constructor) shaded in its own colour under one directional light, a
// half-space as a grey square with grid lines, and contacts drawn over everything: a red dot at each point and
// an orange segment along its normal. The camera is fixed for the whole run (frameBounds of the bodies at their
// start poses, extended to their footprint on any half-space) unless one is given.
// Not thread-safe: an OpenGL context is current on one thread at a time; use one renderer per thread.
#pragma once

#include "unidist/adapters/scene.h"
#include "unidist/render/camera.h"
#include "unidist/render/display_mesh.h"
#include "unidist/render/image.h"

#include <map>
#include <memory>
#include <optional>

namespace unidist::raster {
class OffscreenContext;
}

namespace unidist::render {

struct RenderOptions {
  int width = 640, height = 480;  ///< pixels, 1..8192 each
  double relativeChordError = 2e-3;  ///< display tessellation of curved models (display_mesh.h)
  std::optional<Camera> camera;      ///< none: frame the scene
};

/// The colours the pictures use (RGB, 0..255), for tests and documentation.
struct Palette {
  static constexpr std::uint8_t background[3] = {236, 240, 246};
  static constexpr std::uint8_t contactDot[3] = {230, 0, 0};
  static constexpr std::uint8_t contactNormal[3] = {255, 150, 0};
};

class SceneRenderer {
 public:
  /// Tessellates every model (once per distinct model) and places the camera. Throws InputError for bad options
  /// and std::runtime_error when no off-screen OpenGL context can be made.
  SceneRenderer(const Scene& scene, const RenderOptions& options = {});
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  /// One picture of the bodies (scene order, as the runners report them) and the contacts.
  Image render(const std::vector<BodyState>& bodies, const std::vector<SimContact>& contacts);

  const Camera& camera() const { return camera_; }
  /// World length of a drawn contact normal: 6 % of the picture's height at the camera's target.
  double contactLength() const { return contactLength_; }
  /// The tessellation body i is drawn with.
  const DisplayMesh& displayMesh(std::size_t body) const { return *meshes_[body]; }

 private:
  void drawBody(const DisplayMesh& mesh, const Eigen::Isometry3d& pose, const Eigen::Vector3f& colour) const;
  void drawContacts(const std::vector<SimContact>& contacts) const;

  std::unique_ptr<raster::OffscreenContext> context_;
  RenderOptions options_;
  Camera camera_;
  double contactLength_ = 1;                     ///< world length of a drawn normal
  std::vector<bool> isPlane_;                    ///< per body
  std::vector<Eigen::Vector3f> colours_;         ///< per body
  std::map<const Model*, DisplayMesh> shared_;   ///< one tessellation per distinct bounded model
  std::vector<DisplayMesh> planes_;              ///< one square per half-space body (its extent is the scene's)
  std::vector<const DisplayMesh*> meshes_;       ///< per body, into shared_ or planes_
};

}  // namespace unidist::render
