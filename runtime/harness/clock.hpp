// The harness's clocks: a monotonic time for durations and the UTC time stamp results record.
#pragma once
#include <chrono>
#include <ctime>
#include <string>

namespace sgnlf::harness {

// Seconds on the steady clock (differences only).
inline double now_s() {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}

// "YYYY-MM-DDTHH:MM:SSZ", now.
inline std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

}  // namespace sgnlf::harness
