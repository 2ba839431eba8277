// `sgnlf anatomy --run <run dir> [--out DIR] [--data <dataset>] [--device SPEC]`: the error
// anatomy of a trained run's test views beside the nearest-scan baseline's (docs/anatomy.md):
// renders them as `sgnlf eval` does, writes <out>/anatomy.json and <out>/anatomy/<frame>.png
// (default out: the run folder, where `sgnlf report` finds them) and prints which cause and
// range band each CD direction and the depth MSE come from.
#include <cmath>
#include <cstdio>

#include "apps/command.hpp"
#include "apps/device_profile_option.hpp"
#include "core/config.hpp"
#include "metrics/anatomy_json.hpp"
#include "pipeline/run/anatomy_run.hpp"
#include "pipeline/run/session.hpp"

namespace sgnlf::app {
namespace {

struct AnatomyArgs {
  std::string run, out, data, device, device_profile;
};

std::string cell(double v, bool share) {
  if (!std::isfinite(v)) return "-";  // ASCII keeps printf's columns aligned
  char buf[32];
  std::snprintf(buf, sizeof buf, share ? "%.1f%%" : "%.4g", share ? 100.0 * v : v);
  return buf;
}

void print_table(const Json& j) {
  const auto rows = metrics::anatomy_shares(j.at("model").at("mean"), j.at("naive_baseline").at("mean"));
  std::printf("%-10s %-9s | %-21s | %-21s | %-21s\n", "split", "part", "CD pred->GT",
              "CD GT->pred", "depth MSE");
  std::printf("%-10s %-9s |", "", "");
  for (size_t q = 0; q < metrics::anatomy_quantities().size(); ++q)
    std::printf(" %10s %10s |", "ours", "nearest");
  std::printf("\n");
  for (const auto& r : rows) {
    const bool share = r.split != "total";
    std::printf("%-10s %-9s |", r.split == "total" ? "total m2" : r.split.c_str(), r.part.c_str());
    for (size_t q = 0; q < r.model.size(); ++q)
      std::printf(" %10s %10s |", cell(r.model[q], share).c_str(), cell(r.baseline[q], share).c_str());
    std::printf("\n");
  }
}

const Registrar reg("anatomy", "Split a trained run's test-view errors by cause and band, beside the nearest scan",
                    [](CLI::App& sub) {
  auto a = std::make_shared<AnatomyArgs>();
  sub.add_option("--run", a->run, "Run folder")->required();
  sub.add_option("--out", a->out, "Output folder for anatomy.json and anatomy/ (default: the run folder)");
  sub.add_option("--data", a->data, "Dataset folder (default: the one the run trained on)");
  sub.add_option("--device", a->device, "OpenCL device index or name substring");
  add_device_profile_option(sub, a->device_profile);
  return std::function<int()>([a] {
    pipeline::read_manifest(a->run);  // a folder without run.json fails before the device opens
    cl::Runtime rt(a->device, a->device_profile);
    pipeline::LoadedRun run = pipeline::load_run(rt, a->run, a->data);
    const std::string out = a->out.empty() ? a->run : a->out;
    const Json j = pipeline::anatomy_run(run, out);
    std::printf("%s (%s) on %s, step %ld, %zu test view(s): shares of the mean over the views "
                "(ours beside the nearest training scan)\n",
                j.at("method").get<std::string>().c_str(), j.at("preset").get<std::string>().c_str(),
                j.at("dataset").get<std::string>().c_str(), j.at("step").get<long>(),
                j.at("pictures").size());
    print_table(j);
    std::printf("\ncause: both = range error where both return, missed = the sensor returned and "
                "we did not, false = we returned and the sensor did not; range by the observed "
                "range (a false return's by ours); train = distance to the nearest training-scan "
                "point (docs/anatomy.md)\nwrote %s/anatomy.json and %zu picture(s) in %s/anatomy/ "
                "(ours, nearest scan, observed; magenta = false return, white = missed)\n",
                out.c_str(), j.at("pictures").size(), out.c_str());
    return 0;
  });
});

}  // namespace
}  // namespace sgnlf::app
