// sgnlf: the command-line entry point. Library errors become messages and exit codes here:
// 0 ok, 1 runtime error, 2 usage/config error, 3 no/invalid OpenCL device, 4 regression found.
#include <algorithm>
#include <iostream>

#include "apps/command.hpp"
#include "cl/error.hpp"
#include "core/error.hpp"

namespace sgnlf::app {
std::vector<CommandDef>& registry() {
  static std::vector<CommandDef> r;
  return r;
}
}  // namespace sgnlf::app

int main(int argc, char** argv) {
  using namespace sgnlf;
  CLI::App app{"sgnlf: pose-free LiDAR novel view synthesis (SG-NLF) on OpenCL"};
  app.require_subcommand(1);
  auto& cmds = app::registry();
  std::sort(cmds.begin(), cmds.end(),
            [](const app::CommandDef& a, const app::CommandDef& b) {
              return std::string(a.name) < b.name;
            });
  std::function<int()> run;
  for (auto& c : cmds) {
    CLI::App* sub = app.add_subcommand(c.name, c.help);
    auto fn = c.setup(*sub);
    sub->callback([&run, fn] { run = fn; });
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    return run ? run() : 0;
  } catch (const cl::DeviceError& e) {
    std::cerr << "sgnlf: device error: " << e.what() << "\n";
    return 3;
  } catch (const ConfigError& e) {
    std::cerr << "sgnlf: config error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "sgnlf: error: " << e.what() << "\n";
    return 1;
  }
}
