// A monotonic clock in seconds, injectable: progress lines and their ETAs read time through a
// SecondsClock, so that their tests advance a fake clock instead of sleeping.
#pragma once
#include <chrono>
#include <functional>

namespace sgnlf {

// Seconds on a monotonic clock (only differences mean anything).
using SecondsClock = std::function<double()>;

// The steady clock.
inline SecondsClock steady_seconds() {
  return [] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  };
}

}  // namespace sgnlf
