// Cancellation inside long sequential steps (std::nth_element, std::sort, big copies) that
// have no loop of their own to poll in: a comparator or loop calls the poll on every step,
// which reads the flag every 4096 calls and throws Cancelled once it is set. Counting does not
// change what the algorithm computes, so results are identical when nothing is cancelled.
#pragma once

#include <atomic>
#include <cstdint>
#include <exception>

namespace photon {

struct Cancelled : std::exception {
  const char* what() const noexcept override { return "cancelled"; }
};

class CancelPoll {
 public:
  explicit CancelPoll(const std::atomic<bool>* flag) : flag_(flag) {}
  void operator()() {
    if (flag_ && (++count_ & 0xFFFu) == 0 && flag_->load(std::memory_order_relaxed))
      throw Cancelled();
  }

 private:
  const std::atomic<bool>* flag_;
  uint32_t count_ = 0;
};

}  // namespace photon
