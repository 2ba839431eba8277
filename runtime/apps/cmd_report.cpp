// `sgnlf report RUN_OR_BENCH_DIR [--out FILE] [--renders DIR] [--max-images N]`: writes one
// self-contained HTML page of a run folder or a bench output folder (runtime/report/report.hpp)
// and prints its path. A missing folder or one with neither run.json nor results.json is an
// error naming the path (exit 1); --renders on a bench folder is a usage error (exit 2).
#include <iostream>
#include <memory>

#include "apps/command.hpp"
#include "report/report.hpp"

namespace sgnlf::app {
namespace {

const Registrar reg("report",
                    "Write one self-contained HTML page of a run or bench folder (report.html)",
                    [](CLI::App& sub) {
  auto dir = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  auto opt = std::make_shared<report::ReportOptions>();
  sub.add_option("DIR", *dir, "Run folder (run.json) or bench output folder (results.json)")
      ->required();
  sub.add_option("--out", *out, "Output file (default DIR/report.html)");
  sub.add_option("--renders", opt->renders_dir,
                 "Renders folder of a run (default RUN/renders when it exists)");
  sub.add_option("--max-images", opt->max_images, "Pictures embedded per run at most")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  return std::function<int()>([=] {
    const std::string path = report::write_report(*dir, *out, *opt);
    std::cout << "report: " << path << "\n";
    return 0;
  });
});

}  // namespace
}  // namespace sgnlf::app
