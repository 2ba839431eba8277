// Crash safety of training: the rotating checkpoint pair and its
// fallback when latest.ckpt is corrupt, clear errors that keep the last good checkpoint when the
// output folder cannot be written or the disk is full, and train_log.jsonl continuing from the
// resumed step instead of repeating steps.
#include <catch2/catch.hpp>

#include <sys/resource.h>

#include <csignal>
#include <filesystem>
#include <fstream>

#include "core/config.hpp"
#include "core/error.hpp"
#include "pipeline/train/checkpoint.hpp"
#include "pipeline/train/trainer.hpp"
#include "support/test_device.hpp"
#include "tiny_scene.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;
using namespace sgnlf::pipeline;
namespace fs = std::filesystem;

namespace {

Checkpoint checkpoint_at(long step, size_t n = 1000) {
  Checkpoint ck;
  ck.step = step;
  ck.seed = 5;
  ck.config_hash = 0x1234;
  std::vector<float> p(n);
  for (size_t i = 0; i < n; ++i) p[i] = float(step) + float(i) * 1e-3f;
  ck.arrays = {{"params", p}};
  return ck;
}

std::string contents(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void put(const std::string& p, const std::string& s) {
  std::ofstream(p, std::ios::binary | std::ios::trunc) << s;
}

std::vector<long> logged_steps(const std::string& run_dir) {
  std::ifstream in(run_dir + "/train_log.jsonl");
  std::vector<long> steps;
  std::string line;
  while (std::getline(in, line)) steps.push_back(Json::parse(line).at("step").get<long>());
  return steps;
}

std::vector<float> train_params(const Scene& scene, const TrainConfig& c, const std::string& dir,
                                long stop_at = -1) {
  LidarNerfModel model(test::runtime(), c, float(scene.norm.scale),
                       std::max(c.schedule.rays_per_batch, c.schedule.render_chunk_rays));
  TrainOptions opt;
  opt.run_dir = dir;
  opt.seed = 3;
  opt.stop_at = stop_at;
  opt.show_progress = false;
  train(model, scene, c, opt);
  return model.params();
}

// Limits the size of files this process may write (what a full disk looks like to write()),
// ignoring SIGXFSZ so that write() fails with EFBIG; restored on destruction.
struct FileSizeLimit {
  rlimit old{};
  void (*old_handler)(int) = nullptr;
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &old);
    old_handler = std::signal(SIGXFSZ, SIG_IGN);
    rlimit r = old;
    r.rlim_cur = bytes;
    REQUIRE(setrlimit(RLIMIT_FSIZE, &r) == 0);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &old);
    std::signal(SIGXFSZ, old_handler);
  }
};

}  // namespace

TEST_CASE("rotating checkpoints: a corrupt latest falls back to the previous one",
          "[pipeline][checkpoint][crash]") {
  const std::string dir = test::temp_dir("ckpt_rotate");
  const std::string latest = dir + "/latest.ckpt", prev = dir + "/previous.ckpt";
  CHECK_FALSE(have_checkpoint(latest));
  save_checkpoint_rotating(latest, checkpoint_at(10));
  CHECK_FALSE(fs::exists(prev));  // nothing older yet
  save_checkpoint_rotating(latest, checkpoint_at(20));
  save_checkpoint_rotating(latest, checkpoint_at(30));
  CHECK(load_checkpoint(latest).step == 30);
  CHECK(load_checkpoint(prev).step == 20);
  for (const auto& f : fs::directory_iterator(dir))
    CHECK(f.path().extension() == ".ckpt");  // no temporary file left

  std::string used;
  const std::string good = contents(latest);
  SECTION("a flipped byte") {
    std::string bad = good;
    bad[bad.size() / 2] ^= 0x10;
    put(latest, bad);
  }
  SECTION("cut short") { put(latest, good.substr(0, 100)); }
  SECTION("empty") { put(latest, ""); }
  SECTION("missing (killed between the renames of another writer)") { fs::remove(latest); }
  CHECK(have_checkpoint(latest));
  const Checkpoint ck = load_latest_checkpoint(latest, 0x1234, 5, &used);
  CHECK(ck.step == 20);
  CHECK(used == prev);

  // Both bad: the error names both files.
  put(prev, "junk");
  try {
    load_latest_checkpoint(latest, 0x1234, 5);
    FAIL("expected IoError");
  } catch (const IoError& e) {
    CHECK_THAT(e.what(), Catch::Contains("latest.ckpt") && Catch::Contains("previous.ckpt"));
  }
}

TEST_CASE("a checkpoint of another config is refused, not skipped for an older one",
          "[pipeline][checkpoint][crash]") {
  const std::string dir = test::temp_dir("ckpt_rotate_config");
  const std::string latest = dir + "/latest.ckpt";
  save_checkpoint_rotating(latest, checkpoint_at(10));
  save_checkpoint_rotating(latest, checkpoint_at(20));
  CHECK_THROWS_AS(load_latest_checkpoint(latest, 0x9999, 5), ConfigError);
  CHECK_THROWS_AS(load_latest_checkpoint(latest, 0x1234, 6), ConfigError);
  fs::remove(latest);
  fs::remove(dir + "/previous.ckpt");
  CHECK_THROWS_WITH(load_latest_checkpoint(latest, 0x1234, 5),
                    Catch::Contains("no earlier checkpoint"));
}

TEST_CASE("a full disk fails with the reason and keeps the last good checkpoint",
          "[pipeline][checkpoint][crash]") {
  const std::string dir = test::temp_dir("ckpt_full");
  const std::string latest = dir + "/latest.ckpt";
  save_checkpoint_rotating(latest, checkpoint_at(10, 100));
  save_checkpoint_rotating(latest, checkpoint_at(20, 100));
  const std::string before = contents(latest), prev_before = contents(dir + "/previous.ckpt");
  std::string msg;
  {
    FileSizeLimit limit(64 * 1024);
    try {
      save_checkpoint_rotating(latest, checkpoint_at(30, 100000));  // 400 kB
    } catch (const IoError& e) {
      msg = e.what();
    }
  }
  INFO(msg);
  CHECK_THAT(msg, Catch::Contains("latest.ckpt") && Catch::Contains("write failed") &&
                      Catch::Contains("File too large") && Catch::Contains("left as it was"));
  CHECK(contents(latest) == before);
  CHECK(contents(dir + "/previous.ckpt") == prev_before);
  CHECK_FALSE(fs::exists(latest + ".tmp"));
  CHECK(load_latest_checkpoint(latest, 0x1234, 5).step == 20);
}

TEST_CASE("an unwritable checkpoint folder fails clearly and keeps the last good checkpoint",
          "[pipeline][checkpoint][crash]") {
  // Tests run as root in CI, where file modes do not stop writes; a directory in the place of
  // the temporary file (or of the folder) fails the same system calls a read-only folder does.
  const std::string dir = test::temp_dir("ckpt_unwritable");
  const std::string latest = dir + "/checkpoints/latest.ckpt";
  save_checkpoint_rotating(latest, checkpoint_at(10));
  const std::string before = contents(latest);
  fs::create_directories(latest + ".tmp");
  CHECK_THROWS_WITH(save_checkpoint_rotating(latest, checkpoint_at(20)),
                    Catch::Contains("latest.ckpt") && Catch::Contains("cannot open") &&
                        Catch::Contains("Is a directory"));
  CHECK(contents(latest) == before);
  put(dir + "/blocked", "a file where a folder should be");
  CHECK_THROWS_WITH(save_checkpoint(dir + "/blocked/checkpoints/latest.ckpt", checkpoint_at(1)),
                    Catch::Contains("cannot create the folder"));
}

TEST_CASE("after a crash and resume train_log.jsonl holds each step once",
          "[pipeline][train][crash][device]") {
  const Scene scene = make_scene(test::tiny_dataset());
  const TrainConfig c = test::tiny_config();  // 12 steps, checkpoints every 4, logs every 2
  const std::string full_dir = test::temp_dir("crash_log_full");
  const auto full = train_params(scene, c, full_dir);
  const std::vector<long> full_steps = logged_steps(full_dir);
  REQUIRE(full_steps == std::vector<long>{1, 2, 4, 6, 8, 10, 12});
  CHECK_FALSE(fs::exists(full_dir + "/checkpoints/previous.ckpt"));  // a finished run keeps one

  // Crashed after step 10 was logged, before its checkpoint landed: the folder holds the log up
  // to 10 and the checkpoint of step 8 (stop at 10, then put the step-8 state back as latest).
  const std::string dir = test::temp_dir("crash_log");
  train_params(scene, c, dir, 10);
  const std::string ck = checkpoint_path(dir);
  REQUIRE(load_checkpoint(ck).step == 10);
  fs::copy_file(dir + "/checkpoints/previous.ckpt", ck, fs::copy_options::overwrite_existing);
  REQUIRE(load_checkpoint(ck).step == 8);
  {
    std::ofstream torn(dir + "/train_log.jsonl", std::ios::app);
    torn << "{\"step\": 1";  // and a line the kill cut in half
  }
  const auto resumed = train_params(scene, c, dir);
  CHECK(resumed == full);
  CHECK(logged_steps(dir) == full_steps);  // before the fix: 1 2 4 6 8 10 10 12 (and a torn line)
}

TEST_CASE("a corrupt latest.ckpt resumes from the previous one, bit-identically",
          "[pipeline][train][crash][device]") {
  const Scene scene = make_scene(test::tiny_dataset());
  const TrainConfig c = test::tiny_config();
  const auto full = train_params(scene, c, test::temp_dir("crash_corrupt_full"));
  const std::string dir = test::temp_dir("crash_corrupt");
  train_params(scene, c, dir, 10);
  const std::string ck = checkpoint_path(dir);
  std::string bytes = contents(ck);
  bytes[bytes.size() / 3] ^= 0x01;
  put(ck, bytes);
  CHECK_THROWS_AS(load_checkpoint(ck), IoError);
  const auto resumed = train_params(scene, c, dir);  // before the fix: IoError, nothing to resume
  CHECK(resumed == full);
  CHECK(load_checkpoint(ck).step == 12);
}

TEST_CASE("a checkpoint that cannot be written stops training and keeps the last good one",
          "[pipeline][train][crash][device]") {
  const Scene scene = make_scene(test::tiny_dataset());
  const TrainConfig c = test::tiny_config();
  const std::string dir = test::temp_dir("crash_unwritable");
  train_params(scene, c, dir, 4);
  const std::string ck = checkpoint_path(dir);
  const std::string before = contents(ck);
  fs::create_directories(ck + ".tmp");  // the next checkpoint (step 8) cannot be written
  CHECK_THROWS_WITH(train_params(scene, c, dir),
                    Catch::Contains("latest.ckpt") && Catch::Contains("left as it was"));
  CHECK(contents(ck) == before);
  CHECK(load_checkpoint(ck).step == 4);
  fs::remove_all(ck + ".tmp");
  train_params(scene, c, dir);  // and the run resumes once the folder is writable again
  CHECK(load_checkpoint(ck).step == 12);
}
