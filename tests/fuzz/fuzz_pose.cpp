// Poses "tx ty tz qw qx qy qz" (parsePose): a finite translation and a proper rotation, or InputError.
#include "fuzz_common.h"
#include "unidist/adapters/spec.h"

#include <Eigen/Geometry>

#include <cmath>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace unidist::fuzz;
  if (size > 4096) return -1;
  const std::string text(reinterpret_cast<const char*>(data), size);
  expectValidOrInputError([&] {
    const Eigen::Isometry3d X = unidist::parsePose(text, "--pose-a");
    requireFinite(X.matrix().allFinite(), "pose");
    const Eigen::Matrix3d R = X.linear();
    if (!(R.transpose() * R).isIdentity(1e-9) || std::abs(R.determinant() - 1) > 1e-9)
      finding("pose rotation is not a rotation");
  });
  return 0;
}
