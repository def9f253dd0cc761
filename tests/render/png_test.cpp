// PNG files: a picture written and read back is the same, bytes for bytes; unwritable and unreadable files are
// clear errors naming the file.
#include "unidist/primitives.h"
#include "unidist/render/image.h"
#include "unidist/render/scene_renderer.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace {

using unidist::render::Image;

class PngFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("unidist_png_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  std::filesystem::path dir_;
};

std::string messageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const unidist::InputError& e) {
    return e.what();
  }
  return "";
}

TEST_F(PngFiles, PatternRoundTrips) {
  Image image;
  image.width = 37;  // odd sizes: no row padding assumptions
  image.height = 23;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      image.rgb.insert(image.rgb.end(), {std::uint8_t(7 * x), std::uint8_t(11 * y), std::uint8_t(x ^ y)});
  unidist::render::writePng(path("pattern.png"), image);
  const Image back = unidist::render::readPng(path("pattern.png"));
  EXPECT_EQ(back.width, 37);
  EXPECT_EQ(back.height, 23);
  EXPECT_EQ(back.rgb, image.rgb);
}

TEST_F(PngFiles, RenderedFrameRoundTripsTopRowFirst) {
  unidist::Scene scene;
  unidist::SceneBody ball;
  ball.name = "ball";
  ball.model = std::make_shared<unidist::Sphere>(1);
  ball.mass = 1;
  scene.bodies.push_back(ball);
  unidist::render::RenderOptions options;
  options.width = 48;
  options.height = 40;
  unidist::render::SceneRenderer renderer(scene, options);
  // A contact high in the picture: its dot must come back in the upper half (rows flipped from OpenGL's order).
  const std::vector<unidist::SimContact> contacts = {{{0, 0, 1.3}, {0, 0, 1}, 0}};
  const Image frame = renderer.render({{"ball", Eigen::Isometry3d::Identity(), {}, {}}}, contacts);
  unidist::render::writePng(path("frame.png"), frame);
  const Image back = unidist::render::readPng(path("frame.png"));
  ASSERT_EQ(back.rgb, frame.rgb);
  const auto at = renderer.camera().project(contacts[0].point, 48, 40);
  ASSERT_TRUE(at);
  ASSERT_LT(at->y(), 20);
  const std::uint8_t* p = back.pixel(int(at->x()), int(at->y()));
  EXPECT_EQ(p[0], unidist::render::Palette::contactDot[0]);
  EXPECT_EQ(p[1], unidist::render::Palette::contactDot[1]);
  EXPECT_EQ(p[2], unidist::render::Palette::contactDot[2]);
}

TEST_F(PngFiles, ErrorsNameTheFile) {
  Image image;
  image.width = image.height = 2;
  image.rgb.assign(12, 0);
  const std::string missingDir = path("no/such/dir/x.png");
  const std::string written = messageOf([&] { unidist::render::writePng(missingDir, image); });
  EXPECT_EQ(written.rfind(missingDir + ": cannot write", 0), 0u) << written;
  std::ofstream(path("not.png")) << "not a png";
  const std::string read = messageOf([&] { unidist::render::readPng(path("not.png")); });
  EXPECT_EQ(read.rfind(path("not.png") + ": cannot read", 0), 0u) << read;
  image.rgb.pop_back();
  EXPECT_THROW(unidist::render::writePng(path("short.png"), image), unidist::InputError);
}

}  // namespace
