// Test fixture shared by the reader tests: files written to a scratch directory (removed after each test)
// and the check that loading one fails with a one-line message naming the file and the place.
#pragma once

#include "error_of.h"
#include "unidist/adapters/load.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace unidist::testing {

class ScratchFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("unidist_readers_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& contents) {
    const std::filesystem::path p = dir_ / name;
    std::ofstream(p, std::ios::binary) << contents;
    return p.string();
  }

  /// Loading `contents` as `name` fails with one line starting "<path>" + `where` and holding `fragment`.
  void expectLoadError(const std::string& name, const std::string& contents, const std::string& where,
                       const std::string& fragment) {
    const std::string path = write(name, contents);
    const std::string msg = errorOf([&] { unidist::loadModel(path); });
    EXPECT_EQ(msg.rfind(path + where, 0), 0u) << "message: '" << msg << "'\nexpected to start with: '" << path + where << "'";
    EXPECT_NE(msg.find(fragment), std::string::npos) << "message: '" << msg << "'\nexpected: '" << fragment << "'";
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "message must be one line: " << msg;
  }

  std::filesystem::path dir_;
};

}  // namespace unidist::testing
