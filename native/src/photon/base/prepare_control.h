// How long work (a preparation: photon tracing, a radiosity solve; a render) is watched and
// steered from outside: cancel, stop early, progress and warnings.
#pragma once

#include <atomic>
#include <functional>
#include <string>

namespace photon {

// Reports and controls a long preparation (photon tracing, a radiosity solve).
struct PrepareControl {
  const std::atomic<bool>* cancel = nullptr;      // abandon the render
  const std::atomic<bool>* stop_early = nullptr;  // finish this phase now, keep what is done
  std::function<void(const std::string& status, float fraction)> progress;
  std::function<void(const std::string& warning)> warn;

  bool cancelled() const { return cancel && cancel->load(std::memory_order_relaxed); }
  bool should_stop() const {
    return cancelled() || (stop_early && stop_early->load(std::memory_order_relaxed));
  }
  void report(const std::string& status, float fraction) const {
    if (progress) progress(status, fraction);
  }
};

}  // namespace photon
