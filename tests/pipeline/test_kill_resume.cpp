// Kill and resume: `sgnlf train` killed with SIGKILL at three points (after a
// step between checkpoints, half-way through writing a checkpoint, between the renames of a
// checkpoint) and once at a random time, then resumed, ends with a checkpoint byte-identical to
// an uninterrupted run of the same seed, and with the same train_log.jsonl steps. The kills at
// fixed points use the SGNLF_FAULT_KILL hook (pipeline/train/checkpoint.hpp); the random one is a
// real kill(2) from this process at a time drawn from the project's generator.
#include <catch2/catch.hpp>

#include <signal.h>

#include <filesystem>
#include <fstream>

#include "core/config.hpp"
#include "core/rng.hpp"
#include "pipeline/train/checkpoint.hpp"
#include "pipeline/train/trainer.hpp"
#include "support/files.hpp"
#include "support/spawn.hpp"
#include "support/test_device.hpp"
#include "tiny_scene.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;
namespace fs = std::filesystem;

namespace {

using Outcome = test::ProcessOutcome;

// Runs `sgnlf train --method method` on `data` into `out` (output to <out>.log); `fault` goes to
// SGNLF_FAULT_KILL; kill_after_s >= 0 sends SIGKILL after that many seconds.
Outcome run_train(const std::string& data, const std::string& out, const std::string& fault,
                  double kill_after_s = -1.0, const std::string& method = "lidar-nerf",
                  const std::string& config = "") {
  std::vector<std::string> args = {SGNLF_BIN, "train", "--method", method, "--preset", "smoke",
                                   "--data", data, "--out", out, "--seed", "7"};
  if (!config.empty()) args.insert(args.end(), {"--config", config});
  return test::run_process(args, out + ".log", {"SGNLF_FAULT_KILL=" + fault}, kill_after_s);
}

std::string contents(const std::string& p) { return test::file_contents(p); }

std::vector<long> logged_steps(const std::string& run_dir) {
  std::ifstream in(run_dir + "/train_log.jsonl");
  std::vector<long> steps;
  std::string line;
  while (std::getline(in, line)) steps.push_back(Json::parse(line).at("step").get<long>());
  return steps;
}

long latest_step(const std::string& run) {
  return pipeline::load_checkpoint(pipeline::checkpoint_path(run)).step;
}

}  // namespace

TEST_CASE("sgnlf train killed with SIGKILL and resumed equals the uninterrupted run",
          "[pipeline][train][crash][device]") {
  const std::string root = test::temp_dir("kill_resume");
  const std::string data = root + "/data";
  test::write_tiny_dataset(data);

  // The uninterrupted run: smoke preset, 60 steps, checkpoints every 20, logs every 10.
  const std::string a = root + "/uninterrupted";
  const Outcome full = run_train(data, a, "");
  INFO(contents(a + ".log"));
  REQUIRE(full.exited);
  REQUIRE(full.code == 0);
  REQUIRE(latest_step(a) == 60);

  const std::string b = root + "/killed";
  // 1. After step 30, between the checkpoints of 20 and 40.
  Outcome o = run_train(data, b, "after-step@30");
  CHECK(o.signal == SIGKILL);
  CHECK(latest_step(b) == 20);
  // 2. Half-way through writing the checkpoint of step 40: latest (20) untouched.
  o = run_train(data, b, "checkpoint-partial@40");
  CHECK(o.signal == SIGKILL);
  CHECK(fs::exists(pipeline::checkpoint_path(b) + ".tmp"));
  CHECK(latest_step(b) == 20);
  // 3. Writing the last checkpoint (60): previous already replaced, latest not yet renamed.
  o = run_train(data, b, "checkpoint-linked@60");
  CHECK(o.signal == SIGKILL);
  CHECK(latest_step(b) == 40);
  // 4. At a random time of a resumed run (from 40), drawn from a fixed seed.
  Rng rng(18, 0);
  const double t_kill = full.seconds * rng.uniform_double();
  o = run_train(data, b, "", t_kill);
  INFO("random kill after " << t_kill << " s: " << (o.signal ? "killed" : "finished first"));
  // 5. Resume to the end.
  o = run_train(data, b, "");
  INFO(contents(b + ".log"));
  REQUIRE(o.exited);
  REQUIRE(o.code == 0);

  CHECK(latest_step(b) == 60);
  CHECK(contents(pipeline::checkpoint_path(b)) == contents(pipeline::checkpoint_path(a)));
  CHECK(logged_steps(b) == logged_steps(a));
  CHECK(logged_steps(a) == std::vector<long>{1, 10, 20, 30, 40, 50, 60});
  // `sgnlf train` records where it ran (the report's build row).
  CHECK(load_json_file(a + "/summary.json").at("context").at("build").at("git").is_object());
  CHECK_FALSE(fs::exists(pipeline::checkpoint_path(b) + ".tmp"));
}

namespace {

// `method` with the config overrides in `config` (JSON) on the tiny scene: the uninterrupted run
// to `steps`; then a run killed after step `kill_step` (latest checkpoint `kept`), again half-way
// through writing the checkpoint of `partial_step` (still `kept`), and resumed to the end. Its
// checkpoint must equal the uninterrupted run's byte for byte, and both must log `logged`.
void check_kill_resume(const std::string& name, const std::string& method, const Json& config,
                       long steps, long kill_step, long kept, long partial_step,
                       const std::vector<long>& logged) {
  const std::string root = test::temp_dir(name);
  const std::string data = root + "/data";
  test::write_tiny_dataset(data);
  const std::string cfg = root + "/tiny.json";
  std::ofstream(cfg) << config.dump();
  const std::string a = root + "/uninterrupted";
  const Outcome full = run_train(data, a, "", -1.0, method, cfg);
  INFO(contents(a + ".log"));
  REQUIRE(full.exited);
  REQUIRE(full.code == 0);
  REQUIRE(latest_step(a) == steps);

  const std::string b = root + "/killed";
  Outcome o = run_train(data, b, "after-step@" + std::to_string(kill_step), -1.0, method, cfg);
  CHECK(o.signal == SIGKILL);
  CHECK(latest_step(b) == kept);
  o = run_train(data, b, "checkpoint-partial@" + std::to_string(partial_step), -1.0, method, cfg);
  CHECK(o.signal == SIGKILL);
  CHECK(latest_step(b) == kept);
  o = run_train(data, b, "", -1.0, method, cfg);
  INFO(contents(b + ".log"));
  REQUIRE(o.exited);
  REQUIRE(o.code == 0);
  CHECK(latest_step(b) == steps);
  CHECK(contents(pipeline::checkpoint_path(b)) == contents(pipeline::checkpoint_path(a)));
  CHECK(logged_steps(b) == logged_steps(a));
  CHECK(logged_steps(a) == logged);
}

}  // namespace

TEST_CASE("sg-nlf killed with SIGKILL and resumed equals the uninterrupted run",
          "[pipeline][train][crash][sgnlf][device]") {
  // The whole SG-NLF, shrunk to the tiny scene (28 steps, checkpoints every 7): the kills fall
  // after the adversarial warm-up (4), with the pose graph built and λ ramping (4 → 14), so the
  // resumed run must restore the discriminator and its Adam, the graph and the spectral state.
  check_kill_resume("kill_resume_sgnlf", "sg-nlf", test::tiny_sgnlf_overrides(true), 28, 17, 14,
                    21, {1, 7, 14, 21, 28});
}

TEST_CASE("lidar4d killed with SIGKILL and resumed equals the uninterrupted run",
          "[pipeline][train][crash][lidar4d][device]") {
  // LiDAR4D shrunk to the tiny scene (24 steps, checkpoints every 8): the resumed run must
  // restore both Adam groups (encodings, and the MLPs with the flow field at 0.1·lr) and the
  // flow supervision's schedule.
  check_kill_resume("kill_resume_lidar4d", "lidar4d",
                    Json{{"schedule", {{"iterations", 24}, {"checkpoint_every", 8}, {"log_every", 8},
                                       {"rays_per_batch", 128}, {"render_chunk_rays", 512}}},
                         {"render", {{"n_samples", 16}, {"n_importance", 4}}}},
                    24, 13, 8, 16, {1, 8, 16, 24});
}
