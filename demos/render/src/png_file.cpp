#include "unidist/render/image.h"

#include "unidist/types.h"

#include <png.h>

#include <cerrno>
#include <cstring>

namespace unidist::render {

void writePng(const std::string& path, const Image& image) {
  if (image.width < 1 || image.height < 1 ||
      image.rgb.size() != 3 * static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height))
    throw InputError(path + ": cannot write an empty or inconsistent picture");
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.width);
  png.height = static_cast<png_uint_32>(image.height);
  png.format = PNG_FORMAT_RGB;
  png.flags = PNG_IMAGE_FLAG_FAST;  // frames are many and flat-coloured: speed over the last bytes of size
  errno = 0;
  if (!png_image_write_to_file(&png, path.c_str(), 0, image.rgb.data(), 0, nullptr)) {
    const std::string why = errno ? std::strerror(errno) : png.message;
    png_image_free(&png);
    throw InputError(path + ": cannot write the PNG picture (" + why + ")");
  }
}

Image readPng(const std::string& path) {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str()))
    throw InputError(path + ": cannot read the PNG picture (" + png.message + ")");
  png.format = PNG_FORMAT_RGB;
  Image image;
  image.width = static_cast<int>(png.width);
  image.height = static_cast<int>(png.height);
  image.rgb.resize(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, image.rgb.data(), 0, nullptr)) {
    const std::string why = png.message;
    png_image_free(&png);
    throw InputError(path + ": cannot read the PNG picture (" + why + ")");
  }
  return image;
}

}  // namespace unidist::render
