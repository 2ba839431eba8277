// The app's hooks for the table runner: pipeline::run_method for rows and the datasets module
// for sequences (simulated twins written to disk, or windows of real data under --data-root).
// Built without those modules (CMake: SGNLF_HARNESS_WIRED off), every row is "not implemented".
#pragma once
#include "harness/runner.hpp"

namespace sgnlf::harness {

BenchHooks default_hooks();
// True when this binary was built with the pipeline and datasets wired in.
bool hooks_wired();

}  // namespace sgnlf::harness
