// `sgnlf merge --out DIR CELL...`: combines the cell files of a table run as cells
// (`sgnlf bench --cell K`, runtime/harness/cells.hpp) into DIR/results.json and DIR/table.md,
// equal to the one-process run's apart from the fields results/schema.md "Cells" names.
// `--expect RESULTS` checks that equality against a one-process run (exit 4 when they differ).
#include <iostream>
#include <memory>

#include "apps/command.hpp"
#include "harness/cells.hpp"
#include "harness/runner.hpp"

namespace sgnlf::app {
namespace {

const Registrar reg("merge", "Combine the cell results of a table (sgnlf bench --cell K) into one",
                    [](CLI::App& sub) {
  auto out = std::make_shared<std::string>();
  auto inputs = std::make_shared<std::vector<std::string>>();
  auto expect = std::make_shared<std::string>();
  sub.add_option("--out", *out, "Output folder (results.json, table.md)")->required();
  sub.add_option("CELL", *inputs, "Cell files, or folders holding cell.json")->required();
  sub.add_option("--expect", *expect,
                 "A one-process results.json of the same table: fail (exit 4) unless the merged "
                 "result equals it apart from times, paths and context");
  return std::function<int()>([=] {
    std::vector<std::pair<std::string, Json>> cells;
    std::string command = "sgnlf merge --out " + *out;
    for (const auto& in : *inputs) {
      const std::string path = harness::cell_file_path(in);
      Json j;
      try {
        j = load_json_file(path);
      } catch (const std::exception& e) {
        throw ConfigError("merge: " + path + " is not readable JSON: " + e.what());
      }
      cells.emplace_back(path, std::move(j));
      command += " " + in;
    }
    const Json results = harness::merge_cells(cells, command, *out);
    const auto [json_path, md_path] = harness::write_outputs(results, *out);
    int failed = 0;
    for (const auto& row : results["rows"]) failed += row["status"] == "failed";
    std::cout << "merged " << cells.size() << " cells\nresults: " << json_path
              << "\ntable:   " << md_path << "\n";
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
    return failed ? 1 : 0;
  });
});

}  // namespace
}  // namespace sgnlf::app
