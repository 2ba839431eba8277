// The README's generated tables: one compact table per committed table, row means beside the
// paper's, status and provenance marks; the marked README section is replaced, never guessed.
#include <catch2/catch.hpp>

#include <cstdio>

#include "core/config.hpp"
#include "fake_table.hpp"
#include "harness/summary_table.hpp"

using namespace sgnlf;

TEST_CASE("a table's summary holds its row means beside the paper's", "[harness][summary]") {
  Json r = test::fake_results();
  auto& lidar = test::row(r, "lidar-nerf");
  lidar["paper"] = Json{{"cd", 0.0923}};
  lidar["paper_unverified"] = Json{{"ate_m", 0.17}};
  const double cd = lidar["mean"]["cd"].get<double>();
  char want[32];
  std::snprintf(want, sizeof want, "| %.3f | 0.092 |", cd);
  const std::string md = harness::summary_markdown(r, "results/tables/x/quick/table.md");
  CHECK(md.find("([results/tables/x/quick/table.md](results/tables/x/quick/table.md))") !=
        std::string::npos);
  CHECK(md.find(std::string("| ") + lidar["label"].get<std::string>() + " " + want) !=
        std::string::npos);
  CHECK(md.find("0.170†") != std::string::npos);       // third-party numbers are marked
  CHECK(md.find("not implemented") != std::string::npos);  // rows this build lacks say so

  SECTION("stale and partial rows are marked") {
    lidar["stale"] = true;
    lidar["sequences_not_run"] = Json::array({"kitti360-1728"});
    const std::string m2 = harness::summary_markdown(r, "t.md");
    CHECK(m2.find("(stale preset; 1 of 2 sequences)") != std::string::npos);
  }
  SECTION("a changed mean changes the summary") {
    lidar["mean"]["cd"] = cd + 0.5;
    CHECK(harness::summary_markdown(r, "results/tables/x/quick/table.md") != md);
  }
}

TEST_CASE("the README's marked section is replaced, and a missing marker is an error",
          "[harness][summary]") {
  const std::string text = std::string("intro\n") + harness::kReadmeBegin + "\nold\n" +
                           harness::kReadmeEnd + "\nrest\n";
  const std::string out = harness::replace_marked_section(text, "NEW\n", "README.md");
  CHECK(out == std::string("intro\n") + harness::kReadmeBegin + "\n\nNEW\n\n" +
                   harness::kReadmeEnd + "\nrest\n");
  CHECK(harness::replace_marked_section(out, "NEW\n", "README.md") == out);  // idempotent
  CHECK_THROWS_WITH(harness::replace_marked_section("no markers", "x", "README.md"),
                    Catch::Contains("README.md") && Catch::Contains("markers"));
}
