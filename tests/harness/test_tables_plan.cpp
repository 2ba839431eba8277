// The plan of the committed tables (harness/tables_plan*.hpp) and the run files a merge keeps
// (harness/run_files.hpp), on fake tables written to a temporary root: each cell state made to
// happen (done, stale by config hash, to run, not implemented, not planned, running), plan.json
// refused naming its field, the check failing on a hand-edited PLAN.md and on a running cell that
// is done, and exactly the small run files copied.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "core/config.hpp"
#include "fake_table.hpp"
#include "harness/combine.hpp"
#include "harness/results.hpp"
#include "harness/run_files.hpp"
#include "harness/tables_plan_page.hpp"

using namespace sgnlf;
namespace fs = std::filesystem;

namespace {

// The fake kitti360-standard smoke table (seed 7) with a row and sequence subset.
Json partial(std::vector<std::string> rows, std::vector<std::string> seqs = {}) {
  auto o = test::fake_options();
  o.rows = std::move(rows);
  o.sequences = std::move(seqs);
  return Json::parse(harness::run_table(o, test::fake_hooks(), test::fake_context()).dump());
}

// lidar-nerf's current config hash is the fake runs' own (done); sg-nlf's another (stale).
harness::BenchHooks hooks() {
  auto h = test::fake_hooks();
  h.config_hash = [](const std::string& m, const std::string&) -> std::string {
    if (m == "sg-nlf") return "00000000000000ff";
    if (m != "lidar-nerf") return "";
    return harness::config_hash(Json{{"method", m}, {"iterations", 10}, {"seed", 7}});
  };
  return h;
}

struct TempRoot {
  fs::path dir;
  explicit TempRoot(const std::string& name) : dir(fs::temp_directory_path() / ("sgnlf-" + name)) {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~TempRoot() { fs::remove_all(dir); }
  std::string str() const { return dir.string(); }
};

// A root with the fake kitti360-standard smoke table: lidar-nerf on kitti360-1538 only, sg-nlf
// on both sequences; plan.json as given.
void write_root(const TempRoot& root, const Json& plan) {
  const Json t = harness::combine_tables({{"a/results.json", partial({"lidar-nerf"}, {"kitti360-1538"})},
                                          {"b/results.json", partial({"sg-nlf"})}},
                                         {}, hooks(), "sgnlf merge", "/o");
  fs::create_directories(root.dir / "kitti360-standard" / "smoke");
  write_json_file((root.dir / "kitti360-standard" / "smoke" / "results.json").string(), t);
  write_json_file(harness::plan_json_path(root.str()), plan);
}

Json base_plan() {
  return Json{{"scale", "smoke"},
              {"seeds", {7, 8}},
              {"reference_target", "skylake-avx512"},
              {"order", Json::array({Json{{"rows", {"lidar-nerf"}}, {"why", "first"}}})},
              {"not_planned", Json::array({Json{{"rows", {"lidar-nerf"}}, {"seeds", {8}},
                                                {"reason", "seed 8 for sg-nlf only"}}})}};
}

const harness::PlannedCell& cell(const harness::TablesPlan& p, const std::string& row,
                                 const std::string& seq, uint64_t seed) {
  for (const auto& t : p.tables)
    for (const auto& c : t.cells)
      if (t.name == "kitti360-standard" && c.ref.row == row && c.ref.sequence == seq && c.ref.seed == seed)
        return c;
  throw std::out_of_range("no cell " + row + " " + seq);
}

harness::TablesPlan derive(const TempRoot& root) {
  const auto f = harness::load_tables_plan_file(harness::plan_json_path(root.str()));
  return harness::derive_tables_plan(root.str(), f, hooks(), "plan.json");
}

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

}  // namespace

TEST_CASE("the plan's cell states come from the tables and plan.json", "[harness][plan]") {
  TempRoot root("plan-states");
  Json plan = base_plan();
  plan["running"] = Json::array({Json{{"table", "kitti360-standard"}, {"row", "sg-nlf"},
                                      {"sequence", "kitti360-1728"}, {"seed", 8}, {"by", "test"},
                                      {"since", "now"}}});
  plan["certified"] = Json::array({Json{{"table", "kitti360-standard"}, {"row", "lidar-nerf"},
                                        {"sequence", "kitti360-1538"}, {"seed", 7},
                                        {"commit", "0123456"}, {"how", "same bits"}}});
  write_root(root, plan);
  const auto p = derive(root);
  CHECK(p.problems.empty());
  const auto& done = cell(p, "lidar-nerf", "kitti360-1538", 7);
  CHECK(done.state == "done");
  CHECK(done.commit == "0123456");
  CHECK(done.device == "fake-device");
  CHECK(done.other_target);  // not the reference target
  CHECK(done.train_s == Approx(1.0));
  CHECK(done.certifies == "at 0123456: same bits");
  CHECK(done.results == "kitti360-standard/smoke/results.json");
  CHECK(cell(p, "lidar-nerf", "kitti360-1728", 7).state == "to run");
  CHECK(cell(p, "lidar-nerf", "kitti360-1728", 8).state == "not planned");
  CHECK(cell(p, "lidar-nerf", "kitti360-1728", 8).note == "seed 8 for sg-nlf only");
  const auto& stale = cell(p, "sg-nlf", "kitti360-1728", 7);
  CHECK(stale.state == "stale");
  CHECK(stale.current_hash == "00000000000000ff");
  CHECK(stale.train_s == Approx(2.0));
  CHECK(cell(p, "sg-nlf", "kitti360-1538", 8).state == "to run");
  CHECK(cell(p, "sg-nlf", "kitti360-1728", 8).state == "running");
  CHECK(cell(p, "lidar4d", "kitti360-1538", 7).state == "not implemented");
  // The page: summary counts and the order of what to run next.
  const auto f = harness::load_tables_plan_file(harness::plan_json_path(root.str()));
  const std::string md = harness::render_tables_plan(p, f);
  CHECK(md.find("| [kitti360-standard](#kitti360-standard) | 1 | 2 | 1 | 2 | 2 | 12 | 20 |") !=
        std::string::npos);
  const auto first = md.find("kitti360-standard · LiDAR-NeRF"), later = md.find("kitti360-standard · SG-NLF");
  CHECK(first != std::string::npos);
  CHECK(later != std::string::npos);
  CHECK(first < later);  // lidar-nerf's group first
}

TEST_CASE("PoCL CPU targets are read from device names", "[harness][plan]") {
  CHECK(harness::pocl_cpu_target("pthread-skylake-avx512-AMD EPYC") == "skylake-avx512");
  CHECK(harness::pocl_cpu_target("pthread-haswell-AMD EPYC") == "haswell");
  CHECK(harness::pocl_cpu_target("pthread-skylake-avx512-Intel(R) Xeon(R) Processor") == "skylake-avx512");
  CHECK(harness::pocl_cpu_target("NVIDIA H100 80GB HBM3") == "NVIDIA H100 80GB HBM3");
}

TEST_CASE("a bad plan.json is refused naming its field", "[harness][plan]") {
  const auto refused = [](const Json& j, const std::string& part) {
    try {
      harness::parse_tables_plan_file(j, "results/tables/plan.json");
    } catch (const ConfigError& e) {
      const std::string m = e.what();
      CHECK(m.find("results/tables/plan.json") != std::string::npos);
      CHECK(m.find(part) != std::string::npos);
      return;
    }
    FAIL("accepted: " + j.dump());
  };
  Json ok = base_plan();
  CHECK_NOTHROW(harness::parse_tables_plan_file(ok, "plan.json"));
  Json j = ok;
  j["running"] = Json::array({Json{{"table", "kitti360-standard"}, {"row", "sg-nlf"},
                                   {"sequnce", "kitti360-1728"}, {"seed", 7}, {"by", "x"}, {"since", ""}}});
  refused(j, "running[0]");
  j = ok;
  j["seeds"] = Json::array({"1"});
  refused(j, "seeds");
  j = ok;
  j["colour"] = "red";
  refused(j, "colour");
  j = ok;
  j["certified"] = Json::array({Json{{"table", "t"}, {"row", "r"}, {"sequence", "s"}, {"seed", 7},
                                     {"commit", "not-a-sha"}, {"how", "x"}}});
  refused(j, "certified[0]: 'commit'");
  j = ok;
  j["not_planned"][0].erase("reason");
  refused(j, "not_planned[0]: missing required key 'reason'");
  // Names the table definitions lack.
  j = ok;
  j["running"] = Json::array({Json{{"table", "kitti360-standard"}, {"row", "nope"},
                                   {"sequence", "kitti360-1728"}, {"seed", 9}, {"by", "x"}, {"since", ""}}});
  const auto p = harness::plan_file_name_problems(harness::parse_tables_plan_file(j, "plan.json"), "plan.json");
  REQUIRE(p.size() == 2);
  CHECK(p[0].find("running[0].row: 'nope'") != std::string::npos);
  CHECK(p[1].find("seed 9 is not one of the plan's seeds") != std::string::npos);
}

TEST_CASE("check-tables' plan check: a hand-edited PLAN.md fails, --render fixes it, a running "
          "cell that is done is flagged", "[harness][plan]") {
  TempRoot root("plan-check");
  write_root(root, base_plan());
  const std::string page = harness::plan_page_path(root.str());
  auto p = harness::check_tables_plan(root.str(), hooks());
  REQUIRE(p.size() == 1);
  CHECK(p[0].find("PLAN.md is missing") != std::string::npos);
  write_text_file(page, harness::render_plan_page(root.str(), hooks()));
  CHECK(harness::check_tables_plan(root.str(), hooks()).empty());
  std::string text = read(page);
  text.replace(text.find("| 1 | 2 |"), 9, "| 2 | 1 |");
  write_text_file(page, text);
  p = harness::check_tables_plan(root.str(), hooks());
  REQUIRE(p.size() == 1);
  CHECK(p[0].find("PLAN.md is not the rendering") != std::string::npos);
  CHECK(p[0].find("line ") != std::string::npos);
  write_text_file(page, harness::render_plan_page(root.str(), hooks()));
  CHECK(harness::check_tables_plan(root.str(), hooks()).empty());
  // A cell running that is done, and a certification of a stale cell.
  Json plan = base_plan();
  plan["running"] = Json::array({Json{{"table", "kitti360-standard"}, {"row", "lidar-nerf"},
                                      {"sequence", "kitti360-1538"}, {"seed", 7}, {"by", "x"},
                                      {"since", ""}}});
  plan["certified"] = Json::array({Json{{"table", "kitti360-standard"}, {"row", "sg-nlf"},
                                        {"sequence", "kitti360-1538"}, {"seed", 7},
                                        {"commit", "0123456"}, {"how", "same bits"}}});
  write_json_file(harness::plan_json_path(root.str()), plan);
  write_text_file(page, harness::render_plan_page(root.str(), hooks()));
  p = harness::check_tables_plan(root.str(), hooks());
  REQUIRE(p.size() == 2);
  CHECK(p[0].find("running[0]: kitti360-standard / lidar-nerf / kitti360-1538 / seed 7 is already done") !=
        std::string::npos);
  CHECK(p[1].find("certified[0]") != std::string::npos);
  CHECK(p[1].find("is stale") != std::string::npos);
  // A name the definitions lack; plan.json missing.
  plan = base_plan();
  plan["order"][0]["rows"] = {"lidar-nerf", "no-such-row"};
  write_json_file(harness::plan_json_path(root.str()), plan);
  p = harness::check_tables_plan(root.str(), hooks());
  REQUIRE(!p.empty());
  CHECK(p[0].find("order[0].rows: 'no-such-row'") != std::string::npos);
  fs::remove(harness::plan_json_path(root.str()));
  p = harness::check_tables_plan(root.str(), hooks());
  REQUIRE(p.size() == 1);
  CHECK(p[0].find("plan.json is missing") != std::string::npos);
}

TEST_CASE("merge --keep-run-files keeps exactly each new run's small files", "[harness][plan][merge]") {
  TempRoot root("keep-run-files");
  // A bench output moved from its out_dir (/nonexistent/out) to root/bench: its run folders are
  // found under the file's folder.
  const Json bench = partial({"lidar-nerf"});
  const fs::path in = root.dir / "bench" / "results.json";
  fs::create_directories(in.parent_path());
  write_json_file(in.string(), bench);
  const std::vector<std::string> extra = {"checkpoints/latest.ckpt", "train_log.jsonl",
                                          "trajectories/gt.tum.txt", "trajectories/top_view.svg",
                                          "run.json"};
  for (const char* seq : {"kitti360-1538", "kitti360-1728"}) {
    const fs::path run = root.dir / "bench" / "runs" / "lidar-nerf" / seq;
    for (const auto& name : harness::kept_run_file_names()) {
      fs::create_directories((run / name).parent_path());
      write_text_file((run / name).string(), name + "\n");
    }
    for (const auto& name : extra) {
      fs::create_directories((run / name).parent_path());
      write_text_file((run / name).string(), "not kept\n");
    }
  }
  // One file too large to keep.
  write_text_file((root.dir / "bench/runs/lidar-nerf/kitti360-1728/summary.json").string(),
                  std::string(300 * 1024, ' ') + "{}");
  const fs::path out = root.dir / "table";
  const Json merged = harness::combine_tables({{in.string(), bench}}, {}, hooks(), "sgnlf merge", out.string());
  const auto kept = harness::keep_run_files(merged, {{in.string(), bench}}, out.string());
  std::vector<std::string> found;
  for (const auto& e : fs::recursive_directory_iterator(out))
    if (e.is_regular_file()) found.push_back(e.path().lexically_relative(out).string());
  std::sort(found.begin(), found.end());
  std::vector<std::string> want;
  for (const char* seq : {"kitti360-1538", "kitti360-1728"})
    for (const auto& name : harness::kept_run_file_names())
      if (!(std::string(seq) == "kitti360-1728" && name == "summary.json"))
        want.push_back("runs/lidar-nerf/" + std::string(seq) + "/seed7/" + name);
  std::sort(want.begin(), want.end());
  CHECK(found == want);
  CHECK(kept.copied.size() == want.size());
  REQUIRE(kept.notes.size() == 1);
  CHECK(kept.notes[0].find("summary.json left out") != std::string::npos);
  CHECK(read(out / "runs/lidar-nerf/kitti360-1538/seed7/trajectories/gt.kitti.txt") ==
        "trajectories/gt.kitti.txt\n");
  // Merged again into the committed table with --later-wins, nothing new: the committed runs
  // come from a combined input and are not copied again (their folders are gone).
  fs::remove_all(root.dir / "bench" / "runs");
  const fs::path committed = out / "results.json";
  write_json_file(committed.string(), merged);
  const Json again = harness::combine_tables({{committed.string(), merged}}, {true}, hooks(), "m", out.string());
  CHECK(harness::keep_run_files(again, {{committed.string(), merged}}, out.string()).copied.empty());
  // A new input whose run folder is gone is refused, naming the run.
  try {
    harness::keep_run_files(merged, {{in.string(), bench}}, out.string());
    FAIL("a missing run folder was accepted");
  } catch (const ConfigError& e) {
    CHECK(std::string(e.what()).find("lidar-nerf / kitti360-1538 seed 7") != std::string::npos);
  }
}
