// The markdown renderer: ours beside the paper, "not implemented" and "failed" rows,
// per-sequence tables, the naive baseline, the horizontal ATE column.
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>

#include "fake_table.hpp"
#include "harness/compare.hpp"
#include "harness/markdown.hpp"
#include "harness/tables.hpp"

using namespace sgnlf;

TEST_CASE("markdown: ours beside the paper, not implemented rows, per-sequence tables",
          "[harness]") {
  const Json r = test::fake_results(true);
  const std::string md = harness::render_markdown(r);
  CHECK(md.find("| LiDAR-NeRF | 0.1100 | 0.0923 | +0.0177 |") != std::string::npos);
  CHECK(md.find("| LiDAR4D | not implemented | 0.0894 | — |") != std::string::npos);
  CHECK(md.find("| SG-NLF | failed | 0.0867 | — |") != std::string::npos);
  CHECK(md.find("## Sequence kitti360-1538") != std::string::npos);
  CHECK(md.find("## Sequence kitti360-1728") != std::string::npos);
  CHECK(md.find("fake divergence") != std::string::npos);
  // The naive baseline reported by the runs: mean over sequences (0.2 + 0.3) / 2.
  CHECK(md.find("| *naive baseline (nearest training scan)* | 0.2500 | | | 18.00 | | | — | | |") !=
        std::string::npos);
  CHECK(harness::format_metric("depth_psnr", Json(20.456)) == "20.46");
  CHECK(harness::format_metric("cd", Json()) == "—");
}

TEST_CASE("markdown: the horizontal ATE beside the 3D one, blank where a run lacks it",
          "[harness][ate_h]") {
  CHECK(harness::metric_info("ate_h_m") != nullptr);
  CHECK(harness::metric_info("ate_h_m")->lower_better);
  CHECK(harness::metric_tolerance("ate_h_m", "loose", 0.2) ==
        harness::metric_tolerance("ate_m", "loose", 0.2));
  for (const std::string t : {"kitti360-low", "nuscenes-low", "ablation-nuscenes"}) {
    const auto ex = harness::table_def(t).extra_columns;
    CHECK(std::find(ex.begin(), ex.end(), "ate_h_m") != ex.end());
  }
  // Runs made before ate_h_m (sg-nlf's fake runs report ate_m only, as the committed tables):
  // the column renders "—", and no sequence is said to have planar reference poses.
  Json r = test::fake_results();
  r["columns"] = {"cd"};
  r["extra_columns"] = {"ate_m", "ate_h_m"};
  std::string md = harness::render_markdown(r);
  CHECK(md.find("| ATE (m) ↓ | ATE horizontal (m) ↓ |") != std::string::npos);
  CHECK(md.find("| SG-NLF | 0.0550 | 0.0867 | -0.0317 | 0.0700 | — |") != std::string::npos);
  CHECK(md.find("| SG-NLF | 0.0500 | 0.0700 | — |") != std::string::npos);  // kitti360-1538
  CHECK(md.find("are planar") == std::string::npos);
  // A run that reports it, against planar reference poses: its number, and the sequence's note.
  for (auto& s : test::row(r, "sg-nlf")["sequences"])
    if (s["sequence"] == "kitti360-1538")
      s["pose_metrics"] = {{"ate_m", 0.07}, {"ate_h_m", 0.05}, {"ate_reference", "horizontal"}};
  md = harness::render_markdown(r);
  CHECK(md.find("| SG-NLF | 0.0500 | 0.0700 | 0.0500 |") != std::string::npos);
  CHECK(md.find("The reference poses of kitti360-1538 are planar") != std::string::npos);
  CHECK(md.find("The reference poses of kitti360-1728") == std::string::npos);
}
