// `sgnlf devices [--json] [--device SPEC] [--device-profile cpu|gpu|auto|FILE] [--smoke]`: lists
// every OpenCL platform and device and the selected one's device profile; --smoke builds and runs a small kernel on the selected device against a host reference.
#include <cmath>
#include <cstdio>
#include <iostream>

#include "apps/command.hpp"
#include "apps/device_profile_option.hpp"
#include "cl/runtime.hpp"
#include "core/config.hpp"
#include "core/rng.hpp"

namespace sgnlf::app {
namespace {

Json device_json(const cl::DeviceInfo& d) {
  return Json{{"index", d.index},
              {"platform", d.platform_name},
              {"platform_vendor", d.platform_vendor},
              {"platform_version", d.platform_version},
              {"name", d.name},
              {"vendor", d.vendor},
              {"type", d.type},
              {"version", d.version},
              {"driver_version", d.driver_version},
              {"opencl_c_version", d.opencl_c_version},
              {"compute_units", d.compute_units},
              {"clock_mhz", d.clock_mhz},
              {"global_mem_bytes", d.global_mem_bytes},
              {"local_mem_bytes", d.local_mem_bytes},
              {"local_mem_is_global", d.local_mem_is_global},
              {"max_alloc_bytes", d.max_alloc_bytes},
              {"max_work_group_size", d.max_work_group_size},
              {"fp16", d.fp16},
              {"fp64", d.fp64}};
}

int smoke(const std::string& spec, const std::string& profile) {
  cl::Runtime rt(spec, profile);
  const int n = 1 << 16;
  std::vector<float> x(n), y(n);
  Rng rng(7);
  for (int i = 0; i < n; ++i) {
    x[i] = rng.uniform(-1, 1);
    y[i] = rng.uniform(-1, 1);
  }
  auto bx = cl::Buffer::from(rt, x), by = cl::Buffer::from(rt, y);
  auto k = rt.kernel("common/smoke.cl", "common_saxpy_fwd");
  k.set_args(n, 2.5f, bx, by);
  const double ms = k.launch({size_t(n)}).elapsed_ms();
  const auto out = by.read_vec<float>(n);
  double max_err = 0;
  for (int i = 0; i < n; ++i) max_err = std::max(max_err, double(std::fabs(out[i] - (2.5f * x[i] + y[i]))));
  std::printf("smoke on %s: saxpy n=%d max |device - host| = %.3g, kernel %.3f ms\n",
              rt.device().describe().c_str(), n, max_err, ms);
  if (max_err > 1e-5) {
    std::fprintf(stderr, "sgnlf: smoke kernel disagrees with the host reference\n");
    return 1;
  }
  return 0;
}

const Registrar reg("devices", "List OpenCL platforms and devices", [](CLI::App& sub) {
  auto json = std::make_shared<bool>(false);
  auto run_smoke = std::make_shared<bool>(false);
  auto spec = std::make_shared<std::string>();
  sub.add_flag("--json", *json, "Print JSON");
  sub.add_flag("--smoke", *run_smoke, "Run a small kernel on the selected device");
  sub.add_option("--device", *spec, "Device index or name substring (default: $SGNLF_DEVICE)");
  auto profile = std::make_shared<std::string>();
  add_device_profile_option(sub, *profile);
  return std::function<int()>([=] {
    const auto devices = cl::list_devices();
    // Resolve the selection so that a bad --device / SGNLF_DEVICE fails loudly here.
    const auto selected = cl::select_device(*spec);
    const cl::DeviceProfile prof = cl::resolve_profile(*profile, selected);
    if (*json) {
      Json j = Json::array();
      for (const auto& d : devices) {
        auto e = device_json(d);
        e["selected"] = d.index == selected.index;
        if (d.index == selected.index) e["device_profile"] = prof.to_json();
        j.push_back(e);
      }
      std::cout << j.dump(2) << "\n";
    } else {
      for (const auto& d : devices) {
        std::printf("%s%s\n", d.index == selected.index ? "* " : "  ", d.describe().c_str());
        std::printf("    vendor %s, %s, driver %s, %s\n", d.vendor.c_str(), d.version.c_str(),
                    d.driver_version.c_str(), d.opencl_c_version.c_str());
        std::printf("    %u compute units @ %u MHz, global %.1f GiB, local %.0f KiB%s, max "
                    "work-group %zu, fp16 %s, fp64 %s\n",
                    d.compute_units, d.clock_mhz, d.global_mem_bytes / 1073741824.0,
                    d.local_mem_bytes / 1024.0, d.local_mem_is_global ? " (emulated)" : "",
                    d.max_work_group_size, d.fp16 ? "yes" : "no", d.fp64 ? "yes" : "no");
      }
      std::printf("device profile of the selected device: %s\n", prof.to_json().dump().c_str());
    }
    return *run_smoke ? smoke(std::to_string(selected.index), *profile) : 0;
  });
});

}  // namespace
}  // namespace sgnlf::app
