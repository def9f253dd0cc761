// Resident set size of this process, from /proc/self/status (Linux): what a leak per step would grow.
#pragma once

#include <fstream>
#include <string>

namespace longrun {

/// VmRSS in KiB, or -1 when /proc is not there.
inline long residentKiB() {
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    if (key == "VmRSS:") {
      long kib = -1;
      status >> kib;
      return kib;
    }
    std::getline(status, key);
  }
  return -1;
}

}  // namespace longrun
