// `unidist`: command-line front end of the library. Exit codes: 0 success (also --help, --version),
// 2 bad input or any other error, reported as exactly one stderr line "unidist: error: <what>" with nothing on
// stdout (docs/query-contract.md, "Bad input").
#include "commands.h"

#include "unidist/bullet/version.h"
#include "unidist/ode/version.h"
#include "unidist/types.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <string>

namespace {

constexpr int kExitBadInput = 2;

/// Prints the one error line (line breaks in the message become spaces) and returns the exit code.
int fail(const std::string& message) {
  std::string line = "unidist: error: ";
  for (char c : message) line += (c == '\n' || c == '\r') ? ' ' : c;
  while (!line.empty() && line.back() == ' ') line.pop_back();
  line += '\n';
  std::fflush(stdout);
  std::fwrite(line.data(), 1, line.size(), stderr);
  std::fflush(stderr);
  return kExitBadInput;
}

/// The dial's options of one subcommand (unidist/query_options.h), to learn afterwards which were given.
struct DialOptions {
  CLI::Option *tol, *relTol, *maxIterations, *detailA, *detailB;
};

DialOptions addDialOptions(CLI::App* cmd, unidist::cli::DialArgs& dial) {
  DialOptions o;
  o.tol = cmd->add_option(
      "--tol", dial.tol,
      "Absolute accuracy T >= 0 (default: 1e-9 x the larger bounding-box diagonal; 0: as exact as double allows)");
  o.relTol = cmd->add_option("--rel-tol", dial.relTol,
                             "Accuracy relative to the distance R >= 0: far pairs may be answered more coarsely "
                             "(default 0: off)");
  o.maxIterations = cmd->add_option("--max-iterations", dial.maxIterations,
                                    "Cap N >= 1 on the work of iterative methods; a capped answer keeps honest "
                                    "bounds (default 100000)");
  o.detailA = cmd->add_option("--detail-a", dial.detailA,
                              "Level of detail of A: largest deviation D >= 0 of a cheaper stand-in (NURBS "
                              "tessellation, decimated cloud) answered in its place (default 0: exact)");
  o.detailB = cmd->add_option("--detail-b", dial.detailB, "Level of detail of B (as --detail-a)");
  return o;
}

void recordDial(const DialOptions& o, unidist::cli::DialArgs& dial) {
  dial.hasTol = o.tol->count() > 0;
  dial.hasRelTol = o.relTol->count() > 0;
  dial.hasMaxIterations = o.maxIterations->count() > 0;
  dial.hasDetailA = o.detailA->count() > 0;
  dial.hasDetailB = o.detailB->count() > 0;
}

int run(int argc, char** argv) {
  using unidist::cli::DistanceArgs;
  using unidist::cli::InfoArgs;

  CLI::App app{"unidist: certified signed distance between models of any kind (primitives, meshes, point "
               "clouds, NURBS). Contract: docs/query-contract.md.",
               "unidist"};
  app.set_version_flag("--version", std::string("unidist ") + UNIDIST_VERSION + " (" +
                                        unidist::bullet::engineVersion() + "; " +
                                        unidist::ode::engineConfiguration() + ")");
  app.require_subcommand(1);

  DistanceArgs dist;
  CLI::App* distCmd = app.add_subcommand("distance", "Signed distance, witness points, normal and proved bounds");
  distCmd->add_option("A", dist.a, "Model A: a file (.obj .stl .ply .xyz .unurbs.json .igs) or a primitive spec "
                                   "(sphere:r=1, box:hx=1,hy=2,hz=3, capsule:r=,h=, cylinder:r=,h=, cone:r=,h=, "
                                   "torus:R=,r=, plane:nx=,ny=,nz=,d=)")
      ->required();
  distCmd->add_option("B", dist.b, "Model B (as A)")->required();
  CLI::Option* poseA =
      distCmd->add_option("--pose-a", dist.poseA, "Pose of A: \"tx ty tz qw qx qy qz\" (default: identity)");
  CLI::Option* poseB =
      distCmd->add_option("--pose-b", dist.poseB, "Pose of B: \"tx ty tz qw qx qy qz\" (default: identity)");
  const DialOptions distDial = addDialOptions(distCmd, dist.dial);
  CLI::Option* compute = distCmd->add_option(
      "--compute", dist.compute,
      "What to compute: overlap (stop once overlap or separation is proved), separation (no penetration depth) "
      "or signed-distance (default)");
  CLI::Option* inflateA = distCmd->add_option("--inflate-a", dist.inflateA, "Grow A by a ball of radius R >= 0");
  CLI::Option* inflateB = distCmd->add_option("--inflate-b", dist.inflateB, "Grow B by a ball of radius R >= 0");
  CLI::Option* pd = distCmd->add_option(
      "--pd", dist.pd,
      "Penetration depth method: exact (default) or raster (A and B as unions of convex pieces: an OBJ with one "
      "group per piece; image-space depth, docs/raster.md)");
  CLI::Option* resolution =
      distCmd->add_option("--resolution", dist.resolution, "--pd raster: pixels per cube-face side (default 256)");
  distCmd->add_flag("--json", dist.json, "Print one JSON object");

  InfoArgs info;
  CLI::App* infoCmd = app.add_subcommand("info", "What a model is: type, size, bounds, solidity, memory");
  infoCmd->add_option("A", info.model, "A model file or a primitive spec")->required();
  infoCmd->add_flag("--json", info.json, "Print one JSON object");
  infoCmd->add_flag("--build", info.build,
                    "Build the model's acceleration structures first (queries build them lazily) and report their memory");

  unidist::cli::ContactsArgs cont;
  CLI::App* contCmd =
      app.add_subcommand("contacts", "Local minimum distances within a margin: contact points with normals");
  contCmd->add_option("A", cont.a, "Model A (as for distance)")->required();
  contCmd->add_option("B", cont.b, "Model B (as A)")->required();
  CLI::Option* contPoseA = contCmd->add_option("--pose-a", cont.poseA, "Pose of A (as for distance)");
  CLI::Option* contPoseB = contCmd->add_option("--pose-b", cont.poseB, "Pose of B (as for distance)");
  CLI::Option* margin =
      contCmd->add_option("--margin", cont.margin, "Report local minima with distance <= M >= 0 (default 0)");
  CLI::Option* maxContacts =
      contCmd->add_option("--max-contacts", cont.maxContacts, "At most N contacts, deepest first (default 0: all)");
  const DialOptions contDial = addDialOptions(contCmd, cont.dial);
  contCmd->add_flag("--json", cont.json, "Print one JSON object");

  unidist::cli::SimArgs sim;
  CLI::App* simCmd = app.add_subcommand("sim", "Run a scene file headless in Bullet or ODE with the unidist plugin");
  simCmd->add_option("SCENE", sim.scene, "Scene file (JSON; docs/scenes.md)")->required();
  simCmd->add_option("--engine", sim.engine, "bullet (default) or ode");
  CLI::Option* simSteps = simCmd->add_option("--steps", sim.steps, "Number of steps (default: the scene's)");
  simCmd->add_option("--trajectory", sim.trajectory, "Write poses as CSV to this file");
  CLI::Option* recordEvery =
      simCmd->add_option("--record-every", sim.recordEvery, "Trajectory: every K-th step (default 10)");
  simCmd->add_flag("--json", sim.json, "Print one JSON object");
  CLI::Option* simRender = simCmd->add_option(
      "--render", sim.render, "Write PNG pictures DIR/frame_00000.png, ... (start, every K-th step, last)");
  CLI::Option* simRenderEvery =
      simCmd->add_option("--render-every", sim.renderEvery, "Pictures: every K-th step (default: about 30 frames)");
  CLI::Option* simRenderSize =
      simCmd->add_option("--render-size", sim.renderSize, "Pictures: WxH pixels (default 640x480)");

  unidist::cli::HapticArgs haptic;
  CLI::App* hapticCmd = app.add_subcommand(
      "haptic", "Replay probes moving into and out of contact with a coherent tracker per pair (docs/tracking.md)");
  CLI::Option* hapticScene =
      hapticCmd->add_option("--scene", haptic.scene, "Haptic scene file (JSON; default demos/scenes/haptic.json)");
  CLI::Option* hapticPlot =
      hapticCmd->add_option("--plot", haptic.plot, "Write force-vs-time PNGs into DIR (one per pair, one per probe)");
  hapticCmd->add_flag("--json", haptic.json, "Print one JSON object");

  // CLI11 would call an unknown subcommand an unexpected argument; say what it is and what exists.
  std::string known;
  bool isKnown = false;
  for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
    known += (known.empty() ? "'" : ", '") + sub->get_name() + "'";
    isKnown = isKnown || (argc >= 2 && sub->get_name() == argv[1]);
  }
  if (argc >= 2 && argv[1][0] != '-' && !isKnown)
    return fail(std::string("unknown subcommand '") + argv[1] + "' (expected " + known + "; see --help)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --version: print and exit 0
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    if (argc < 2) return fail("missing subcommand (expected " + known + "; see --help)");
    std::string where;  // "distance: B is required" rather than "B is required"
    for (const CLI::App* sub : app.get_subcommands()) where = sub->get_name() + ": ";
    return fail(where + e.what());
  }

  dist.hasPoseA = poseA->count() > 0;
  dist.hasPoseB = poseB->count() > 0;
  recordDial(distDial, dist.dial);
  dist.hasCompute = compute->count() > 0;
  dist.hasInflateA = inflateA->count() > 0;
  dist.hasInflateB = inflateB->count() > 0;
  dist.hasPd = pd->count() > 0;
  dist.hasResolution = resolution->count() > 0;
  cont.hasPoseA = contPoseA->count() > 0;
  cont.hasPoseB = contPoseB->count() > 0;
  cont.hasMargin = margin->count() > 0;
  cont.hasMaxContacts = maxContacts->count() > 0;
  recordDial(contDial, cont.dial);
  sim.hasSteps = simSteps->count() > 0;
  sim.hasRecordEvery = recordEvery->count() > 0;
  sim.hasRender = simRender->count() > 0;
  sim.hasRenderEvery = simRenderEvery->count() > 0;
  sim.hasRenderSize = simRenderSize->count() > 0;
  haptic.hasScene = hapticScene->count() > 0;
  haptic.hasPlot = hapticPlot->count() > 0;
  const std::string out = distCmd->parsed()   ? unidist::cli::runDistance(dist)
                          : contCmd->parsed() ? unidist::cli::runContacts(cont)
                          : simCmd->parsed()  ? unidist::cli::runSim(sim)
                          : hapticCmd->parsed() ? unidist::cli::runHaptic(haptic)
                                              : unidist::cli::runInfo(info);
  std::fwrite(out.data(), 1, out.size(), stdout);
  return std::fflush(stdout) == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const unidist::InputError& e) {
    return fail(e.what());
  } catch (const std::exception& e) {
    return fail(std::string("internal error: ") + e.what());
  } catch (...) {
    return fail("internal error (unknown exception)");
  }
}
