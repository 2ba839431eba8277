#include "cl/shared_runtime.hpp"

#include <mutex>

namespace sgnlf::cl {
namespace {

// A plain pointer, not a static unique_ptr: its release must never run during exit
// (shared_runtime.hpp says why).
Runtime* g_shared = nullptr;
std::mutex g_mutex;

}  // namespace

Runtime& shared_runtime() {
  std::lock_guard<std::mutex> lock(g_mutex);
  if (!g_shared) g_shared = new Runtime();
  return *g_shared;
}

bool shared_runtime_open() {
  std::lock_guard<std::mutex> lock(g_mutex);
  return g_shared != nullptr;
}

void release_shared_runtime() {
  Runtime* rt = nullptr;
  {
    std::lock_guard<std::mutex> lock(g_mutex);
    rt = g_shared;
    g_shared = nullptr;
  }
  delete rt;
}

}  // namespace sgnlf::cl
