// A headless OpenGL context (OSMesa: software rendering, no GPU, no display) with its own colour, depth and
// stencil buffers. Image-space queries and the pictures of the demos both render through one of these.
// An OpenGL context is current on one thread at a time: use one OffscreenContext per thread.
#pragma once

#include <memory>
#include <vector>

namespace unidist::raster {

class OffscreenContext {
 public:
  /// RGBA8 colour, 24-bit depth and 8-bit stencil of width × height pixels. Throws std::runtime_error when
  /// OSMesa cannot create the context; InputError for a size outside 1..8192.
  OffscreenContext(int width, int height);
  ~OffscreenContext();
  OffscreenContext(const OffscreenContext&) = delete;
  OffscreenContext& operator=(const OffscreenContext&) = delete;

  /// Makes the context current on the calling thread with its buffers at width × height (growing or shrinking
  /// them as needed). Every GL call must follow this on the same thread.
  void makeCurrent(int width, int height);
  void makeCurrent() { makeCurrent(width_, height_); }

  int width() const { return width_; }
  int height() const { return height_; }
  /// The colour buffer after glFinish(): width × height RGBA bytes, bottom row first (OpenGL's order).
  const std::vector<unsigned char>& colour();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::vector<unsigned char> colour_;
  int width_ = 0, height_ = 0;
};

}  // namespace unidist::raster
