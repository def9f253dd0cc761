// The subcommands of `unidist`. Each validates all of its input before it writes anything, so bad input leaves
// stdout empty; errors are thrown (InputError for bad input) and reported by main() as one stderr line.
#pragma once

#include <string>

namespace unidist::cli {

struct DistanceArgs {
  std::string a, b;
  std::string poseA, poseB;
  std::string tol;
  std::string inflateA, inflateB;
  std::string pd, resolution;
  // Whether each option was given: an empty value given on purpose ("--tol ''") is bad input, not "absent".
  bool hasPoseA = false, hasPoseB = false, hasTol = false, hasInflateA = false, hasInflateB = false;
  bool hasPd = false, hasResolution = false;
  bool json = false;
};

struct InfoArgs {
  std::string model;
  bool json = false;
  bool build = false;  ///< build every lazily built structure first, to report what it costs
};

struct ContactsArgs {
  std::string a, b;
  std::string poseA, poseB;
  std::string margin, maxContacts;
  bool hasPoseA = false, hasPoseB = false, hasMargin = false, hasMaxContacts = false;
  bool json = false;
};

struct SimArgs {
  std::string scene;
  std::string engine = "bullet";
  std::string steps, trajectory, recordEvery;
  std::string render, renderEvery, renderSize;  // --render DIR: PNG frames (demos/render)
  bool hasSteps = false, hasRecordEvery = false;
  bool hasRender = false, hasRenderEvery = false, hasRenderSize = false;
  bool json = false;
};

struct HapticArgs {
  std::string scene;  ///< default: demos/scenes/haptic.json
  std::string plot;   ///< --plot DIR: force-vs-time PNGs
  bool hasScene = false, hasPlot = false;
  bool json = false;
};

/// Each returns the text for stdout; the caller writes it only when the whole command succeeded.
std::string runDistance(const DistanceArgs& args);
std::string runInfo(const InfoArgs& args);
std::string runContacts(const ContactsArgs& args);
std::string runSim(const SimArgs& args);
std::string runHaptic(const HapticArgs& args);

}  // namespace unidist::cli
