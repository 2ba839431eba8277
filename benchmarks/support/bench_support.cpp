#include "support/bench_support.hpp"

#include <cstring>
#include <memory>

extern char** environ;

namespace sgnlf::bench {

cl::Runtime& runtime() {
  static std::unique_ptr<cl::Runtime> rt = [] {
    auto r = std::make_unique<cl::Runtime>();
    return r;
  }();
  add_device_context();
  return *rt;
}

void add_device_context() {
  static bool done = false;
  if (done) return;
  done = true;
  const auto d = cl::select_device();
  benchmark::AddCustomContext("sgnlf_device", d.name);
  benchmark::AddCustomContext("sgnlf_platform", d.platform_name + " " + d.platform_version);
  benchmark::AddCustomContext("sgnlf_driver", d.driver_version);
  for (char** e = environ; *e; ++e)
    if (std::strncmp(*e, "POCL_", 5) == 0) {
      const char* eq = std::strchr(*e, '=');
      if (eq) benchmark::AddCustomContext(std::string(*e, size_t(eq - *e)), eq + 1);
    }
}

}  // namespace sgnlf::bench
