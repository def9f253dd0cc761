// Peers of the tolerance dial on the same cases, each swept over its own accuracy dial: FCL (primitive and mesh
// pairs: distance_tolerance and abs_err), OpenCASCADE (BRepExtrema_DistShapeShape's deflection, NURBS pairs),
// Bullet (GJK-EPA on convex hulls of the NURBS sphere tessellated ever finer). A peer only answers the cases it
// can (e.g. FCL's meshes have no penetration depth: apart cases only); its rows say so in the method name.
#pragma once

#include "bench/dial_stats.h"
#include "core/dial_cases.h"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <functional>
#include <string>

namespace dial {

/// A peer's call for one case at one setting, ready to time (empty: the peer does not answer this case), and
/// the setting as a tolerance relative to the case's size.
struct Prepared {
  std::function<double()> call;
  double tolerance = 0;
};

/// Whether the call returns at all: run once in a child process, since FCL's libccd EPA can fail an assertion
/// (abort) on some penetrating inputs at tight tolerances.
inline bool survives(const std::function<double()>& call) {
  std::fflush(nullptr);
  const pid_t child = fork();
  if (child == 0) {
    const int devNull = open("/dev/null", O_WRONLY);  // the peer's assertion message: counted, not printed
    dup2(devNull, 2);
    (void)call();
    _exit(0);
  }
  int status = 0;
  waitpid(child, &status, 0);
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

/// One CSV row per setting over the cases the peer answers. A failed answer (NaN) counts as an infinite error;
/// with `probe`, a call that aborts the process is left out of the row and counted on stderr.
template <class Prepare>
void peerRows(const Family& f, const std::string& method, int settings, Prepare&& prepare, bool probe = false) {
  for (int k = 0; k < settings; ++k) {
    std::vector<Sample> samples;
    std::vector<double> tolerances;
    int aborted = 0;
    for (const Case& c : f.cases) {
      const Prepared p = prepare(c, k);
      if (!p.call) continue;
      if (probe && !survives(p.call)) {
        ++aborted;
        continue;
      }
      double value = 0;
      Sample s;
      s.micros = medianMicros(p.call, value, 10000, 7);
      s.error = std::isfinite(value) ? std::abs(value - c.truth) / c.size : std::numeric_limits<double>::infinity();
      samples.push_back(s);
      tolerances.push_back(p.tolerance);
      traceAnswer(f.name, method, c.what, p.tolerance, value, c.truth, s.micros);
    }
    if (aborted)
      std::fprintf(stderr, "  %s %s at %.0e: %d of %zu cases abort the process, left out\n", f.name.c_str(),
                   method.c_str(), quantile(tolerances, 0.5), aborted, samples.size() + static_cast<std::size_t>(aborted));
    if (samples.empty()) continue;
    printRow(f.name, method, quantile(tolerances, 0.5), samples, false);
  }
}

void fclPeers(const Family& f);     // dial_fcl.cpp, built when FCL is installed
void occtPeers(const Family& f);    // dial_occt.cpp, built when OpenCASCADE is installed
void bulletPeers(const Family& f);  // dial_bullet.cpp (Bullet is always there: the plugin needs it)

inline void runPeers(const Family& f) {
#ifdef UNIDIST_DIAL_FCL
  fclPeers(f);
#endif
#ifdef UNIDIST_DIAL_OCCT
  occtPeers(f);
#endif
  bulletPeers(f);
}

}  // namespace dial
