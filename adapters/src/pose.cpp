// Poses "tx ty tz qw qx qy qz": world = R(q)·local + t with q = (w, x, y, z) normalised.
#include "unidist/adapters/spec.h"

#include <cctype>
#include <string>
#include <vector>

namespace unidist {

Eigen::Isometry3d parsePose(const std::string& text, std::string_view what) {
  static constexpr const char* kNames[7] = {"tx", "ty", "tz", "qw", "qx", "qy", "qz"};
  std::vector<std::string_view> tokens;
  const std::string_view s(text);
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    const std::size_t start = i;
    while (i < s.size() && !std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    if (i > start) tokens.push_back(s.substr(start, i - start));
  }
  const std::string prefix(what);
  if (tokens.size() != 7)
    throw InputError(prefix + ": expected 7 numbers \"tx ty tz qw qx qy qz\", got " + std::to_string(tokens.size()));
  double v[7];
  for (int k = 0; k < 7; ++k) v[k] = parseNumber(tokens[static_cast<std::size_t>(k)], prefix + " " + kNames[k]);

  Eigen::Vector4d q(v[3], v[4], v[5], v[6]);
  // Scale by the largest component first: 1e-200 or 1e200 components neither underflow nor overflow the norm.
  const double m = q.cwiseAbs().maxCoeff();
  if (!(m > 0)) throw InputError(prefix + ": zero quaternion (qw qx qy qz all 0)");
  q /= m;
  q.normalize();
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).toRotationMatrix();
  X.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
  return X;
}

}  // namespace unidist
