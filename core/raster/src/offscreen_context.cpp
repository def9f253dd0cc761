#include "unidist/raster/offscreen_context.h"

#include "unidist/types.h"

#include <GL/osmesa.h>

#include <stdexcept>
#include <string>

namespace unidist::raster {

struct OffscreenContext::Impl {
  OSMesaContext context = nullptr;
};

namespace {
void checkSize(int width, int height) {
  if (width < 1 || height < 1 || width > 8192 || height > 8192)
    throw InputError("off-screen buffer of " + std::to_string(width) + " x " + std::to_string(height) +
                     " pixels: each side must be 1..8192");
}
}  // namespace

OffscreenContext::OffscreenContext(int width, int height) : impl_(std::make_unique<Impl>()) {
  checkSize(width, height);
  impl_->context = OSMesaCreateContextExt(OSMESA_RGBA, 24, 8, 0, nullptr);
  if (!impl_->context) throw std::runtime_error("OSMesa could not create an off-screen OpenGL context");
  makeCurrent(width, height);
}

OffscreenContext::~OffscreenContext() {
  if (impl_->context) OSMesaDestroyContext(impl_->context);
}

void OffscreenContext::makeCurrent(int width, int height) {
  checkSize(width, height);
  const std::size_t bytes = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4;
  if (colour_.size() != bytes) colour_.assign(bytes, 0);
  width_ = width;
  height_ = height;
  if (!OSMesaMakeCurrent(impl_->context, colour_.data(), GL_UNSIGNED_BYTE, width, height))
    throw std::runtime_error("OSMesa could not bind a " + std::to_string(width) + " x " + std::to_string(height) +
                             " buffer");
}

const std::vector<unsigned char>& OffscreenContext::colour() {
  glFinish();
  return colour_;
}

}  // namespace unidist::raster
