// The one Runtime a whole binary shares (the test and benchmark binaries), opened on first use
// (SGNLF_DEVICE or the default device, select_device()) and released by
// release_shared_runtime(), which the binary's main() calls before it returns.
//
// Why an explicit release before main() returns, and not the destructor of a static object
// (or an atexit handler): exit() first destroys the calling thread's thread_local objects and
// only then runs static destructors and atexit handlers (C++ [basic.start.term]/1; glibc's
// exit() calls __call_tls_dtors before the exit handlers). An OpenCL implementation may keep
// per-thread state that every API call uses. Oclgrind 21.10's runtime does: each cl* entry
// point pushes its name onto a thread_local std::stack (for its error messages), so the
// clReleaseProgram / clReleaseContext that a static Runtime's destructor made at exit wrote
// into that freed stack, and the heap corruption aborted the process in free() ("corrupted
// double-linked list"; valgrind: "Invalid write ... inside a block free'd by
// __call_tls_dtors"). Every test binary aborted that way under Oclgrind, after all its tests
// had passed. Released from main(), the order is right on any implementation: the kernels and
// buffers the tests or benchmarks made are gone with their scopes, then ~Runtime releases the
// programs, the queue and last the context.
//
// A process that ends without the release (std::exit, a crash) leaves the Runtime to the
// operating system: no OpenCL call is made during exit, where it is not safe.
#pragma once
#include "cl/runtime.hpp"

namespace sgnlf::cl {

// Opens the shared Runtime on the first call; later calls return the same one.
Runtime& shared_runtime();
// True between the first shared_runtime() and release_shared_runtime().
bool shared_runtime_open();
// Releases the shared Runtime and every OpenCL object it owns (no-op when none is open); a
// later shared_runtime() opens a new one. Objects made from it must be gone by then.
void release_shared_runtime();

}  // namespace sgnlf::cl
