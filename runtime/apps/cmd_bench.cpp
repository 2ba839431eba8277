// `sgnlf bench --table T --scale S [--data-root DIR] [--real-root DIR] [--seed N | --seeds
// A,B,C] [--rows A,B] [--sequences X,Y] --out DIR`: runs every row (or the chosen ones) of a
// table on every sequence (or the chosen ones) with every seed (runtime/harness), records the
// context and the device's roofline, and writes <out>/results.json (results/schema.md) and
// <out>/table.md. `--cells` lists the table's independent cells (row × sequence × seed);
// `--cell K --out DIR` runs one and writes DIR/cell.json, for `sgnlf merge` (cmd_merge.cpp).
#include <filesystem>
#include <iostream>
#include <memory>
#include <type_traits>

#include "apps/command.hpp"
#include "apps/device_profile_option.hpp"
#include "cl/runtime.hpp"
#include "core/config.hpp"
#include "core/log.hpp"
#include "harness/cells.hpp"
#include "harness/context.hpp"
#include "harness/estimate.hpp"
#include "harness/roofline.hpp"
#include "harness/runner.hpp"
#include "harness/tables.hpp"
#include "harness/wiring.hpp"
#include "pipeline/run/method.hpp"

namespace sgnlf::app {
namespace {

template <class T>
std::string join_list(const std::string& flag, const std::vector<T>& v) {
  std::string s;
  for (const auto& x : v) {
    std::string item;
    if constexpr (std::is_same_v<T, std::string>) item = x;
    else item = std::to_string(x);
    s += (s.empty() ? flag : ",") + item;
  }
  return s;
}

std::string join_names(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : " | ") + n;
  return s;
}

int list_tables() {
  for (const auto& name : harness::table_names()) {
    const auto t = harness::table_def(name);
    std::cout << name << ": " << t.title << "\n  rows:";
    for (const auto& r : t.rows)
      std::cout << " " << r.method
                << (pipeline::method_implemented(r.method) ? "" : " (not implemented)");
    std::cout << "\n";
    for (const auto& [scale, seqs] : t.scales) {
      std::cout << "  " << scale << ":";
      for (const auto& s : seqs)
        std::cout << " " << s.name << (s.is_real_dir() ? " (real: " + s.real_dir + ")" : "");
      std::cout << "\n";
    }
  }
  return 0;
}

const Registrar reg("bench", "Run a table of the paper (every row on every sequence)",
                    [](CLI::App& sub) {
  auto o = std::make_shared<harness::BenchOptions>();
  auto list = std::make_shared<bool>(false);
  auto no_roofline = std::make_shared<bool>(false);
  sub.add_option("--table", o->table, join_names(harness::table_names()));
  sub.add_option("--scale", o->scale, join_names(harness::scale_names()))->capture_default_str();
  sub.add_option("--data-root", o->data_root, "Real KITTI-360 / nuScenes in their own layout");
  sub.add_option("--real-root", o->real_root,
                 "Folder of the real datasets that a synthetic scale's real sequences read "
                 "(default $SGNLF_SHARED_DIR/data/real, else ../shared/data/real); a sequence "
                 "whose folder is missing is skipped and recorded");
  auto* seed_opt = sub.add_option("--seed", o->seed, "Seed of every run")->capture_default_str();
  auto* seeds_opt =
      sub.add_option("--seeds", o->seeds,
                     "Run every cell with each of these seeds (comma-separated): mean ± sample "
                     "standard deviation over seeds, each seed's values kept")
          ->delimiter(',');
  sub.add_option("--out", o->out_dir, "Output folder");
  sub.add_option("--device", o->device, "OpenCL device index or name (default $SGNLF_DEVICE)");
  add_device_profile_option(sub, o->device_profile);
  sub.add_option("--rows", o->rows, "Only these rows (comma-separated methods; see --list)")
      ->delimiter(',');
  sub.add_option("--sequences", o->sequences, "Only these sequences of the scale (comma-separated)")
      ->delimiter(',');
  sub.add_flag("--no-roofline", *no_roofline, "Skip the roofline probe (~1-2 s)");
  sub.add_flag("--list", *list, "List the tables, rows and sequences");
  auto cells = std::make_shared<bool>(false);
  auto cell = std::make_shared<long>(-1);
  sub.add_flag("--cells", *cells,
               "List the table's independent cells (K, method, sequence, seed; tab-separated)");
  auto* cell_opt = sub.add_option("--cell", *cell,
                                  "Run only cell K (see --cells) and write <out>/cell.json "
                                  "for sgnlf merge");
  auto estimate_only = std::make_shared<bool>(false);
  auto estimate_from = std::make_shared<std::string>();
  sub.add_flag("--estimate", *estimate_only,
               "Print the run's estimated time (per cell and in all) and exit without running");
  sub.add_option("--estimate-from", *estimate_from,
                 "A previous results.json of this table and scale to estimate the time from "
                 "(default results/tables/<table>/<scale>/results.json when it exists)");
  return std::function<int()>([=] {
    if (*list) return list_tables();
    if (o->table.empty()) throw ConfigError("bench: --table is required (see --list)");
    if (seed_opt->count() && seeds_opt->count())
      throw ConfigError("bench: --seed and --seeds exclude each other (--seeds " +
                        join_list("", o->seeds) + ", --seed " + std::to_string(o->seed) + ")");
    if (seeds_opt->count() && o->seeds.empty())
      throw ConfigError("bench: --seeds needs at least one seed");
    if (*cells && cell_opt->count())
      throw ConfigError("bench: --cells lists the cells, --cell K runs one: give one of them");
    o->roofline = !*no_roofline;
    if (*cells) {  // --out is not needed to list them
      if (o->out_dir.empty()) o->out_dir = ".";
      const auto plan = harness::plan_table(*o, harness::default_hooks());
      for (const auto& line : harness::cell_lines(plan)) std::cout << line << "\n";
      std::cerr << plan.cells.size() << " cells (K, method, sequence, seed); run one with "
                << "--cell K --out DIR, combine with sgnlf merge --out DIR CELL_DIR...\n";
      return 0;
    }
    if (!cell_opt->count()) {
      // The estimate comes first: a whole table can take minutes or days.
      harness::BenchOptions planning = *o;  // --out is not needed to plan
      if (planning.out_dir.empty()) planning.out_dir = ".";
      const auto plan = harness::plan_table(planning, harness::default_hooks());
      const std::string from = !estimate_from->empty()
                                   ? *estimate_from
                                   : "results/tables/" + o->table + "/" + o->scale + "/results.json";
      if (!estimate_from->empty() || std::filesystem::exists(from)) {
        const auto est = harness::estimate_table(plan, o->scale, load_json_file(from), from);
        std::cout << "bench: " << est.summary() << "\n";
        if (*estimate_only) {
          for (size_t i = 0; i < est.cells.size(); ++i) {
            const auto& c = est.cells[i];
            const auto& pc = plan.cells[i];
            std::cout << "  cell " << c.index << "\t" << pc.method << "\t" << pc.sequence
                      << "\tseed " << pc.seed << "\t"
                      << (c.seconds >= 0 ? harness::format_duration(c.seconds) + " (" + c.basis + ")"
                                         : std::string("never measured"))
                      << "\n";
          }
          return 0;
        }
      } else {
        std::cout << "bench: " << plan.cells.size()
                  << " cell(s); no previous run of this table and scale to estimate the time from ("
                  << from << ")\n";
        if (*estimate_only) return 0;
      }
    }
    const std::string seed_flag = o->seeds.empty() ? " --seed " + std::to_string(o->seed)
                                                   : join_list(" --seeds ", o->seeds);
    o->command = "sgnlf bench --table " + o->table + " --scale " + o->scale +
                 (o->data_root.empty() ? "" : " --data-root " + o->data_root) +
                 (o->real_root.empty() ? "" : " --real-root " + o->real_root) +
                 seed_flag + (cell_opt->count() ? " --cell " + std::to_string(*cell) : "") +
                 " --out " + o->out_dir +
                 (o->device.empty() ? "" : " --device " + o->device) +
                 (o->device_profile.empty() ? "" : " --device-profile " + o->device_profile) +
                 (o->roofline ? "" : " --no-roofline") + join_list(" --rows ", o->rows) +
                 join_list(" --sequences ", o->sequences);
    o->validate();
    if (!harness::hooks_wired())
      log::warn("bench: built without the pipeline/datasets modules: every row is 'not implemented'");
    const auto dev = cl::select_device(o->device);
    const cl::DeviceProfile profile = cl::resolve_profile(o->device_profile, dev);
    Json context = harness::context_block(&dev, &profile);
    if (o->roofline) {
      log::info("bench: measuring the device roofline on ", dev.describe());
      cl::Runtime rt(dev, o->device_profile);
      context["roofline"] = harness::measure_roofline(rt);
    } else {
      context["roofline"] = nullptr;
    }
    if (cell_opt->count()) {
      const Json c = harness::run_cell(*o, harness::default_hooks(), *cell, context);
      std::cout << "cell:    " << harness::write_cell(c, o->out_dir) << "\n";
      const std::string st = c["outcome"]["status"];
      if (st == "failed")
        std::cerr << "sgnlf bench: cell " << *cell << " failed: " << c["outcome"]["error"].get<std::string>() << "\n";
      return st == "failed" ? 1 : 0;
    }
    const Json results = harness::run_table(*o, harness::default_hooks(), context);
    const auto [json_path, md_path] = harness::write_outputs(results, o->out_dir);
    int failed = 0;
    for (const auto& row : results["rows"]) failed += row["status"] == "failed";
    std::cout << "results: " << json_path << "\ntable:   " << md_path << "\n";
    if (failed) std::cerr << "sgnlf bench: " << failed << " row(s) failed, see " << md_path << "\n";
    return failed ? 1 : 0;
  });
});

}  // namespace
}  // namespace sgnlf::app
