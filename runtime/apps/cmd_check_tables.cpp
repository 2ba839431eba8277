// `sgnlf check-tables [ROOT]`: the committed tables (ROOT, default results/tables:
// <table>/<scale>/{results.json,table.md}) against this build's table definitions, methods and
// config hashes, and each table.md against the rendering of its results.json
// (runtime/harness/table_check.hpp). Exit 4 when a table differs. `--render` first rewrites
// every table.md from its results.json (a change of the markdown renderer). `--readme FILE`
// also checks FILE's generated tables section (runtime/harness/summary_table.hpp) against the
// committed quick tables; with `--render` it rewrites that section. The plan of the tables
// (ROOT/plan.json, ROOT/PLAN.md: runtime/harness/tables_plan_page.hpp) is checked too: PLAN.md
// must be the rendering of the tables and plan.json, and plan.json must name only cells of the
// table definitions and no running cell that is done; `--render` rewrites PLAN.md; `--no-plan`
// leaves the plan out (a folder of tables without one).
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>

#include "apps/command.hpp"
#include "harness/markdown.hpp"
#include "harness/summary_table.hpp"
#include "harness/table_check.hpp"
#include "harness/tables_plan_page.hpp"
#include "harness/wiring.hpp"

namespace sgnlf::app {
namespace {
namespace fs = std::filesystem;

const Registrar reg("check-tables",
                    "Check the committed tables (results/tables) against this build's table "
                    "definitions (exit 4 when one differs)",
                    [](CLI::App& sub) {
  auto root = std::make_shared<std::string>("results/tables");
  auto render = std::make_shared<bool>(false);
  sub.add_option("ROOT", *root, "Folder of <table>/<scale>/ tables")->capture_default_str();
  sub.add_flag("--render", *render, "Rewrite every table.md from its results.json first");
  auto readme = std::make_shared<std::string>();
  auto no_plan = std::make_shared<bool>(false);
  sub.add_flag("--no-plan", *no_plan, "Do not check (or render) ROOT/PLAN.md and ROOT/plan.json");
  sub.add_option("--readme", *readme,
                 "Also check this file's generated tables section (the quick tables' means) "
                 "against ROOT; with --render, rewrite it");
  return std::function<int()>([=] {
    if (*render && fs::is_directory(*root))
      for (const auto& e : fs::recursive_directory_iterator(*root))
        if (e.path().filename() == "results.json") {
          const fs::path md = e.path().parent_path() / "table.md";
          write_text_file(md.string(), harness::render_markdown(load_json_file(e.path().string())));
          std::cout << "rendered " << md.string() << "\n";
        }
    const harness::BenchHooks hooks = harness::default_hooks();
    if (*render && !*no_plan) {
      const std::string page = harness::plan_page_path(*root);
      write_text_file(page, harness::render_plan_page(*root, hooks));
      std::cout << "rendered " << page << "\n";
    }
    size_t n = 0;
    auto problems = harness::check_committed_tables(*root, hooks, &n);
    if (!*no_plan)
      for (auto& p : harness::check_tables_plan(*root, hooks)) problems.push_back(std::move(p));
    if (!readme->empty()) {
      std::ifstream in(*readme, std::ios::binary);
      if (!in) throw IoError(*readme + ": cannot open for reading");
      const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      const std::string want = harness::replace_marked_section(
          text, harness::summary_tables(*root, "quick", "results/tables"), *readme);
      if (*render && want != text) {
        write_text_file(*readme, want);
        std::cout << "rendered the tables of " << *readme << "\n";
      } else if (want != text) {
        problems.push_back(*readme + ": its tables differ from the committed quick tables "
                           "(sgnlf check-tables --render --readme " + *readme + ")");
      }
    }
    for (const auto& p : problems) std::cout << "DIFFERS " << p << "\n";
    std::cout << n << " table(s) in " << *root << ", " << problems.size() << " problem(s)\n";
    if (n == 0) {
      std::cerr << "sgnlf check-tables: no table found under " << *root << "\n";
      return 4;
    }
    return problems.empty() ? 0 : 4;
  });
});

}  // namespace
}  // namespace sgnlf::app
