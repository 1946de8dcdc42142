#pragma once
// Wall-time bounds in tests (cancel latency) are scaled by PHOTON_TIMING_SLACK, default 1.
// The sanitizer run sets it: AddressSanitizer and UndefinedBehaviorSanitizer slow the code
// several times over, and the unscaled bounds are checked by the normal build's run.
#include <cstdlib>

namespace photon {

inline double timing_slack() {
  const char* v = std::getenv("PHOTON_TIMING_SLACK");
  const double s = v && *v ? std::atof(v) : 1.0;
  return s >= 1.0 ? s : 1.0;
}

}  // namespace photon
