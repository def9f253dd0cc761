// The subcommands of `unidist`. Each validates all of its input before it writes anything, so bad input leaves
// stdout empty; errors are thrown (InputError for bad input) and reported by main() as one stderr line.
#pragma once

#include <string>

namespace unidist {
struct QueryOptions;
}

namespace unidist::cli {

/// The query dial (unidist/query_options.h, docs/dial.md) as given to `distance` and `contacts`:
/// --tol, --rel-tol, --max-iterations, --detail-a, --detail-b.
struct DialArgs {
  std::string tol, relTol, maxIterations, detailA, detailB;
  // Whether each option was given: an empty value given on purpose ("--tol ''") is bad input, not "absent".
  bool hasTol = false, hasRelTol = false, hasMaxIterations = false, hasDetailA = false, hasDetailB = false;
};

/// Checks every given dial option (InputError naming the option) and sets it in `options`; absent ones keep
/// the library's defaults.
void applyDial(const DialArgs& args, QueryOptions& options);

struct DistanceArgs {
  std::string a, b;
  std::string poseA, poseB;
  DialArgs dial;
  std::string compute;  ///< overlap | separation | signed-distance
  std::string inflateA, inflateB;
  std::string pd, resolution;
  // Whether each option was given: an empty value given on purpose ("--pd ''") is bad input, not "absent".
  bool hasPoseA = false, hasPoseB = false, hasCompute = false, hasInflateA = false, hasInflateB = false;
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
  DialArgs dial;
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
