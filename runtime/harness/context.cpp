#include "harness/context.hpp"

#include <sys/resource.h>
#include <sys/utsname.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>
#include <thread>

#include "core/config.hpp"

extern char** environ;

namespace sgnlf::harness {
namespace {

// Runs a shell command and returns its stdout (trimmed), or nullopt-like flag on failure.
bool run_capture(const std::string& cmd, std::string& out) {
  out.clear();
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return false;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) out.append(buf.data(), n);
  const int rc = pclose(p);
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r' || out.back() == ' '))
    out.pop_back();
  return rc == 0;
}

std::string read_first(const std::string& path, const std::string& key) {
  std::ifstream f(path);
  std::string line;
  while (std::getline(f, line)) {
    if (line.compare(0, key.size(), key) != 0) continue;
    auto pos = line.find_first_of(":=", key.size());
    if (pos == std::string::npos) continue;
    std::string v = line.substr(pos + 1);
    const auto b = v.find_first_not_of(" \t\"");
    const auto e = v.find_last_not_of(" \t\"");
    return b == std::string::npos ? "" : v.substr(b, e - b + 1);
  }
  return "";
}

}  // namespace

Json git_info() {
  const std::string root = SGNLF_SOURCE_ROOT;
  const std::string git = "git -C '" + root + "' ";
  std::string sha, status, describe;
  if (run_capture(git + "rev-parse HEAD 2>/dev/null", sha) && sha.size() >= 40) {
    run_capture(git + "status --porcelain 2>/dev/null", status);
    run_capture(git + "describe --always --dirty 2>/dev/null", describe);
    int changed = 0;
    std::istringstream s(status);
    for (std::string line; std::getline(s, line);) changed += !line.empty();
    return Json{{"sha", sha}, {"dirty", changed > 0}, {"changed_paths", changed},
                {"describe", describe}, {"source", "git"}};
  }
  const Json b = build_info();
  return Json{{"sha", b["configure_git_sha"]}, {"dirty", nullptr}, {"changed_paths", nullptr},
              {"describe", ""}, {"source", "configure"}};
}

Json machine_info() {
  Json m;
  m["cpu_model"] = read_first("/proc/cpuinfo", "model name");
  m["logical_cores"] = std::thread::hardware_concurrency();
  const std::string mem = read_first("/proc/meminfo", "MemTotal");
  m["mem_total_kib"] = mem.empty() ? Json(nullptr) : Json(std::stoll(mem));
  const std::string os = read_first("/etc/os-release", "PRETTY_NAME");
  m["os"] = os;
  struct utsname u;
  if (uname(&u) == 0) {
    m["kernel"] = std::string(u.sysname) + " " + u.release;
    m["arch"] = u.machine;
  }
  char host[256] = {0};
  m["hostname"] = gethostname(host, sizeof host - 1) == 0 ? std::string(host) : "";
  return m;
}

Json opencl_info(const cl::DeviceInfo& d) {
  return Json{{"platform", d.platform_name},
              {"platform_vendor", d.platform_vendor},
              {"platform_version", d.platform_version},
              {"device", d.name},
              {"device_vendor", d.vendor},
              {"device_type", d.type},
              {"device_version", d.version},
              {"driver_version", d.driver_version},
              {"opencl_c_version", d.opencl_c_version},
              {"compute_units", d.compute_units},
              {"clock_mhz", d.clock_mhz},
              {"global_mem_bytes", d.global_mem_bytes},
              {"fp16", d.fp16},
              {"fp64", d.fp64}};
}

Json pocl_env() {
  Json env = Json::object();
  for (char** e = environ; *e; ++e) {
    if (std::strncmp(*e, "POCL_", 5) != 0) continue;
    const char* eq = std::strchr(*e, '=');
    if (eq) env[std::string(*e, size_t(eq - *e))] = std::string(eq + 1);
  }
  return env;
}

long peak_rss_kib() {
  struct rusage r;
  if (getrusage(RUSAGE_SELF, &r) != 0) return -1;
  return r.ru_maxrss;  // KiB on Linux
}

Json context_block(const cl::DeviceInfo* device, const cl::DeviceProfile* profile) {
  Json c;
  c["git"] = git_info();
  c["build"] = build_info();
  c["build"]["git"] = build_git();
  c["machine"] = machine_info();
  c["opencl"] = device ? opencl_info(*device) : Json(nullptr);
  c["pocl_env"] = pocl_env();
  const char* sel = std::getenv("SGNLF_DEVICE");
  c["sgnlf_device_env"] = sel ? Json(sel) : Json(nullptr);
  if (profile)
    c["device_profile"] = profile->to_json();
  else if (device)
    c["device_profile"] = cl::resolve_profile("", *device).to_json();
  else
    c["device_profile"] = nullptr;
  return c;
}

std::vector<std::pair<std::string, std::string>> flatten(const Json& j, const std::string& prefix) {
  std::vector<std::pair<std::string, std::string>> out;
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) {
      auto sub = flatten(it.value(), prefix.empty() ? it.key() : prefix + "." + it.key());
      out.insert(out.end(), sub.begin(), sub.end());
    }
  } else if (j.is_string()) {
    out.emplace_back(prefix, j.get<std::string>());
  } else {
    out.emplace_back(prefix, j.dump());
  }
  return out;
}

}  // namespace sgnlf::harness
