// `sgnlf merge --out DIR INPUT...`: one table from its pieces, written as DIR/results.json and
// DIR/table.md. The inputs are either
//   - cell files of one table run as cells (`sgnlf bench --cell K`, runtime/harness/cells.hpp):
//     the result equals the one-process run's apart from the fields results/schema.md "Cells"
//     names; `--expect RESULTS` checks that equality (exit 4 when they differ); or
//   - results.json files of the same table and scale holding some of its rows, sequences or
//     seeds (partial runs, other commits; runtime/harness/combine.hpp, results/schema.md
//     "Combined tables"): every row of the table, "not run" where no input ran it, each run's
//     source and staleness; a cell run with several seeds becomes a several-seed entry.
//     `--later-wins` lets a later input replace an earlier one's different result.
// The kind is read from the first input; the others must be of the same kind.
// `--keep-run-files` copies the small files of every run taken from a new input (metrics.json,
// summary.json, the KITTI trajectories) to DIR/runs/<method>/<sequence>/seed<k>/
// (runtime/harness/run_files.hpp).
#include <filesystem>
#include <iostream>
#include <memory>

#include "apps/command.hpp"
#include "core/config.hpp"
#include "harness/cells.hpp"
#include "harness/combine.hpp"
#include "harness/run_files.hpp"
#include "harness/runner.hpp"
#include "harness/wiring.hpp"

namespace sgnlf::app {
namespace {

const Registrar reg("merge",
                    "Combine a table's cell results (sgnlf bench --cell K), or partial results.json "
                    "files of one table, into one table",
                    [](CLI::App& sub) {
  auto out = std::make_shared<std::string>();
  auto inputs = std::make_shared<std::vector<std::string>>();
  auto expect = std::make_shared<std::string>();
  auto later_wins = std::make_shared<bool>(false);
  auto keep_files = std::make_shared<bool>(false);
  auto share = std::make_shared<bool>(false);
  sub.add_option("--out", *out, "Output folder (results.json, table.md)")->required();
  sub.add_option("INPUT", *inputs,
                 "Cell files or folders holding cell.json; or results.json files (or folders "
                 "holding one) of one table and scale, of any seeds")
      ->required();
  sub.add_option("--expect", *expect,
                 "Cells only: a one-process results.json of the same table: fail (exit 4) unless "
                 "the merged result equals it apart from times, paths and context");
  sub.add_flag("--later-wins", *later_wins,
               "results.json inputs: where two inputs have different runs of the same row, "
               "sequence and seed, the later input (in the order given) replaces the earlier; without "
               "it such a conflict is refused");
  sub.add_flag("--share-cells", *share,
               "results.json inputs: accept another table's results of the same scale and data and "
               "take its runs of this table's rows on the sequences both tables define alike (the "
               "same cells: a row two tables share is run once); the rest of it is left out and "
               "listed in combined_from.shared");
  sub.add_flag("--keep-run-files", *keep_files,
               "Copy each new run's metrics.json, summary.json and KITTI trajectories from its run "
               "folder to OUT/runs/<method>/<sequence>/seed<k>/ (files over 200 KB left out)");
  return std::function<int()>([=] {
    std::vector<std::pair<std::string, Json>> files;
    std::string command = "sgnlf merge --out " + *out + (*later_wins ? " --later-wins" : "") +
                          (*share ? " --share-cells" : "");
    bool tables = false;
    for (size_t i = 0; i < inputs->size(); ++i) {
      const std::string& in = (*inputs)[i];
      const bool dir_with_results = std::filesystem::is_regular_file(
          std::filesystem::path(in) / "results.json");
      const std::string path = dir_with_results ? (std::filesystem::path(in) / "results.json").string()
                                                : harness::cell_file_path(in);
      Json j;
      try {
        j = load_json_file(path);
      } catch (const std::exception& e) {
        throw ConfigError("merge: " + path + " is not readable JSON: " + e.what());
      }
      if (i == 0) tables = harness::is_results_table(j);
      if (harness::is_results_table(j) != tables)
        throw ConfigError("merge: " + files.front().first + " and " + path +
                          " are of different kinds (a results.json table and a cell file)");
      files.emplace_back(path, std::move(j));
      command += " " + in;
    }
    if (!tables && (*later_wins || *share))
      throw ConfigError(std::string("merge: ") + (*later_wins ? "--later-wins" : "--share-cells") +
                        " is for results.json inputs");
    if (tables && !expect->empty()) throw ConfigError("merge: --expect is for cell files");
    const Json results =
        tables ? harness::combine_tables(files, harness::CombineOptions{*later_wins, *share},
                                         harness::default_hooks(), command, *out)
               : harness::merge_cells(files, command, *out);
    if (*keep_files) {
      const auto kept = harness::keep_run_files(results, files, *out);
      for (const auto& n : kept.notes) std::cout << "note: " << n << "\n";
      std::cout << "kept " << kept.copied.size() << " run file(s) under " << *out << "/runs\n";
    }
    const auto [json_path, md_path] = harness::write_outputs(results, *out);
    int failed = 0, stale = 0, not_run = 0;
    for (const auto& row : results["rows"]) {
      failed += row["status"] == "failed";
      stale += row.value("stale", Json()) == Json(true);
      not_run += row["status"] == "not_run";
    }
    std::cout << "merged " << files.size() << (tables ? " results" : " cells") << "\nresults: "
              << json_path << "\ntable:   " << md_path << "\n";
    if (tables)
      std::cout << not_run << " row(s) not run, " << stale << " row(s) with a stale config\n";
    const Json no_shared = Json::array();
    for (const auto& sh : tables && results.contains("combined_from")
                              ? results["combined_from"].value("shared", no_shared)
                              : no_shared)
      std::cout << "shared from " << sh.value("input", "") << " (table " << sh.value("table", "")
                << "): " << sh["taken"].size() << " row × sequence taken, "
                << sh["left_out"].size() << " left out\n";
    if (!expect->empty()) {
      const auto diff = harness::table_differences(results, load_json_file(*expect));
      if (!diff.empty()) {
        std::cout << "DIFFERENT from " << *expect << " at:\n";
        for (const auto& d : diff) std::cout << "  " << d << "\n";
        return 4;
      }
      std::cout << "equal to " << *expect << " (apart from times, paths and context)\n";
    }
    if (failed) std::cerr << "sgnlf merge: " << failed << " row(s) failed, see " << md_path << "\n";
    return failed && !tables ? 1 : 0;
  });
});

}  // namespace
}  // namespace sgnlf::app
