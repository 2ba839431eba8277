// Shared benchmark helpers: the benchmark device and the context block (device strings)
// added to Google Benchmark's JSON output.
#pragma once
#include <benchmark/benchmark.h>

#include "cl/runtime.hpp"

namespace sgnlf::bench {

// The Runtime all benchmarks of a binary share (SGNLF_DEVICE or the default device).
cl::Runtime& runtime();

// Adds device name, driver and POCL_* environment to the benchmark context (once).
void add_device_context();

}  // namespace sgnlf::bench
