// A record of what a Runtime's queue was asked to do, launch by launch: each kernel launch with
// its work-items and the size of its largest buffer argument, each blocking transfer (a
// Buffer::read or Buffer::write, which wait for the queue), each non-blocking write
// (Buffer::write_async, which does not) and each Runtime::finish. For
// auditing the shape of a training step (tests/pipeline/test_step_parallelism.cpp: does every
// kernel over many elements launch many work-items, how often does a step wait for the
// device), not for timing: it records no times and changes nothing in the launches.
// Runtime::set_trace(&trace) starts recording into `trace`, set_trace(nullptr) stops.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

namespace sgnlf::cl {

struct TracedLaunch {
  std::string kernel;
  size_t work_items = 0;            // product of the global sizes
  size_t largest_buffer_bytes = 0;  // the largest buffer argument bound at the launch
  // The elements (4-byte words) the launch works on when its launcher says
  // (Kernel::launch's trace_elements): a kernel addressing a slice of a larger buffer (a
  // module's entries of the flat gradient, a scratch arena) gives its own count; 0 when not
  // given, where the largest buffer argument stands for it.
  size_t elements = 0;
  size_t element_count() const { return elements ? elements : largest_buffer_bytes / 4; }
};

struct TracedTransfer {
  bool read = false;  // device → host (else host → device)
  size_t bytes = 0;
  // The kernel launched last before it in this trace, "(trace start)" if none: where in the
  // step it happens.
  std::string after_kernel;
};

struct LaunchTrace {
  void add_transfer(bool read, size_t bytes) {
    blocking_transfers.push_back(
        {read, bytes, launches.empty() ? std::string("(trace start)") : launches.back().kernel});
  }
  void add_async_transfer(size_t bytes) {
    async_transfers.push_back(
        {false, bytes, launches.empty() ? std::string("(trace start)") : launches.back().kernel});
  }
  std::vector<TracedLaunch> launches;
  std::vector<TracedTransfer> blocking_transfers;
  std::vector<TracedTransfer> async_transfers;  // non-blocking writes (no wait)
  long finishes = 0;  // Runtime::finish() calls
  void clear() { *this = LaunchTrace{}; }
};

}  // namespace sgnlf::cl
