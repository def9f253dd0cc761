// `unidist sim --render DIR` as a black box: the number of frames, their size, the report, and bad input.
#include "run_unidist.h"
#include "unidist/render/image.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace {

using unidist::testing::run;

class RenderCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("unidist_render_cli_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
    // A ball dropped 1 cm onto a floor: it touches within the run, so late frames have contacts.
    scene_ = (dir_ / "drop.json").string();
    std::ofstream(scene_) << R"({"dt": 0.004, "steps": 20, "bodies": [
      {"name": "floor", "model": "plane:nx=0,ny=0,nz=1,d=0", "static": true},
      {"name": "ball", "model": "sphere:r=0.1", "pose": [0, 0, 0.11, 1, 0, 0, 0], "mass": 1}]})";
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::vector<std::string> frames(const std::string& sub) const {
    std::vector<std::string> out;
    for (const auto& entry : std::filesystem::directory_iterator(dir_ / sub)) out.push_back(entry.path().string());
    std::sort(out.begin(), out.end());
    return out;
  }

  void expectBadInput(const std::vector<std::string>& args, const std::string& fragment) {
    const unidist::testing::Outcome r = run(args);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_NE(r.err.find("unidist: error: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }

  std::filesystem::path dir_;
  std::string scene_;
};

TEST_F(RenderCli, WritesEveryKthStepAndTheLast) {
  for (const std::string engine : {"bullet", "ode"}) {
    SCOPED_TRACE(engine);
    const std::string out = (dir_ / ("frames_" + engine)).string();
    // Steps 0, 6, 12, 18 and the last (20).
    const auto r = run({"sim", scene_, "--engine", engine, "--render", out, "--render-every", "6", "--render-size",
                        "64x48"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("frames: 5 PNG pictures of 64 x 48 in " + out), std::string::npos) << r.out;
    const std::vector<std::string> files = frames("frames_" + engine);
    ASSERT_EQ(files.size(), 5u);
    for (int i = 0; i < 5; ++i) {
      EXPECT_EQ(std::filesystem::path(files[static_cast<std::size_t>(i)]).filename().string(),
                "frame_0000" + std::to_string(i) + ".png");
      const unidist::render::Image image = unidist::render::readPng(files[static_cast<std::size_t>(i)]);
      EXPECT_EQ(image.width, 64);
      EXPECT_EQ(image.height, 48);
    }
  }
}

TEST_F(RenderCli, DefaultIsAboutThirtyFramesAndJsonCountsThem) {
  const std::string out = (dir_ / "default").string();
  const auto r = run({"sim", scene_, "--steps", "60", "--render", out, "--render-size", "32x24", "--json"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("\"frames\": 31"), std::string::npos) << r.out;  // every 2nd step from 0 to 60
  EXPECT_EQ(frames("default").size(), 31u);
  EXPECT_EQ(unidist::render::readPng(frames("default").front()).width, 32);
}

TEST_F(RenderCli, BadInputIsOneClearLine) {
  const std::string out = (dir_ / "bad").string();
  for (const std::string size : {"0x10", "64", "64x", "x48", "64x48x2", "-64x48", "9000x10", "6.5x10", ""})
    expectBadInput({"sim", scene_, "--render", out, "--render-size", size}, "--render-size");
  expectBadInput({"sim", scene_, "--render", out, "--render-every", "0"}, "--render-every");
  expectBadInput({"sim", scene_, "--render-every", "5"}, "need --render");
  expectBadInput({"sim", scene_, "--render", ""}, "--render needs a directory");
  // A directory that cannot be made: its parent is a file.
  std::ofstream(dir_ / "file") << "x";
  const std::string underFile = (dir_ / "file" / "frames").string();
  expectBadInput({"sim", scene_, "--render", underFile}, underFile + ": cannot create the frame directory");
  expectBadInput({"sim", scene_, "--render", (dir_ / "file").string()}, "--render needs a directory, not a file");
  // A directory that exists but cannot be written (root writes anywhere: then the run simply succeeds).
  const std::filesystem::path locked = dir_ / "locked";
  std::filesystem::create_directories(locked);
  std::filesystem::permissions(locked, std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
  if (::geteuid() != 0)
    expectBadInput({"sim", scene_, "--render", locked.string()}, (locked / "frame_00000.png").string() + ": cannot write");
  EXPECT_FALSE(std::filesystem::exists(out)) << "bad options are found before anything is written";
}

}  // namespace
