// Checkpoints: exact round trip, atomic write, and clear errors for corrupt, truncated or
// foreign files and for a different config or seed.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "core/config.hpp"
#include "core/error.hpp"
#include "pipeline/train/checkpoint.hpp"
#include "support/test_device.hpp"

using namespace sgnlf;
using namespace sgnlf::pipeline;

namespace {
Checkpoint sample_checkpoint() {
  Checkpoint ck;
  ck.step = 1234;
  ck.seed = 99;
  ck.config_hash = 0xABCDEF0123456789ull;
  ck.best_loss = 0.25;
  ck.smoothed_loss = 0.5;
  std::vector<float> a(1000), b(17);
  for (size_t i = 0; i < a.size(); ++i) a[i] = float(i) * 0.001f - 0.3f;
  for (size_t i = 0; i < b.size(); ++i) b[i] = -float(i);
  ck.arrays = {{"params", a}, {"adam_m", b}};
  return ck;
}
std::string contents(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}
void put(const std::string& p, const std::string& s) {
  std::ofstream(p, std::ios::binary | std::ios::trunc) << s;
}
}  // namespace

TEST_CASE("checkpoint round trip is exact", "[pipeline][checkpoint]") {
  const std::string dir = test::temp_dir("ckpt_roundtrip");
  const std::string path = dir + "/a.ckpt";
  const Checkpoint ck = sample_checkpoint();
  save_checkpoint(path, ck);
  CHECK_FALSE(std::filesystem::exists(path + ".tmp"));
  const Checkpoint back = load_checkpoint_for(path, ck.config_hash, ck.seed);
  CHECK(back.step == ck.step);
  CHECK(back.best_loss == ck.best_loss);
  CHECK(back.smoothed_loss == ck.smoothed_loss);
  REQUIRE(back.arrays.size() == 2);
  CHECK(back.array("params") == ck.arrays[0].second);
  CHECK(back.array("adam_m", 17) == ck.arrays[1].second);
  CHECK_THROWS_AS(back.array("adam_v"), IoError);
  CHECK_THROWS_AS(back.array("params", 999), IoError);
}

TEST_CASE("doubles packed into float slots round-trip bit for bit, empty vectors included",
          "[pipeline][checkpoint]") {
  // The empty case is for the sanitizer build: memcpy from an empty vector's null data() was
  // undefined behaviour (UBSan, a pose graph without edges).
  CHECK(pack_doubles({}).empty());
  CHECK(unpack_doubles({}).empty());
  CHECK(unpack_doubles({1.0f}).empty());  // half a double: nothing
  const std::vector<double> v = {0.1, -3.5e300, 1e-310, 42.0};
  const std::vector<float> packed = pack_doubles(v);
  CHECK(packed.size() == 2 * v.size());
  CHECK(unpack_doubles(packed) == v);
  // An empty array survives a checkpoint too.
  const std::string dir = test::temp_dir("ckpt_empty_array");
  Checkpoint ck = sample_checkpoint();
  ck.arrays.push_back({"pose_graph.edges", pack_doubles({})});
  save_checkpoint(dir + "/e.ckpt", ck);
  const Checkpoint back = load_checkpoint_for(dir + "/e.ckpt", ck.config_hash, ck.seed);
  CHECK(back.array("pose_graph.edges", 0).empty());
}

TEST_CASE("corrupt, truncated and foreign checkpoints are refused", "[pipeline][checkpoint]") {
  const std::string dir = test::temp_dir("ckpt_bad");
  const std::string path = dir + "/a.ckpt";
  save_checkpoint(path, sample_checkpoint());
  const std::string good = contents(path);

  std::string flipped = good;
  flipped[200] ^= 0x10;
  put(path, flipped);
  CHECK_THROWS_WITH(load_checkpoint(path), Catch::Contains("checksum"));

  put(path, good.substr(0, good.size() / 2));
  CHECK_THROWS_AS(load_checkpoint(path), IoError);

  put(path, "hello, not a checkpoint at all");
  CHECK_THROWS_WITH(load_checkpoint(path), Catch::Contains("magic"));

  CHECK_THROWS_WITH(load_checkpoint(dir + "/missing.ckpt"), Catch::Contains("missing.ckpt"));

  put(path, good);
  CHECK_THROWS_AS(load_checkpoint_for(path, 1, 99), ConfigError);
  CHECK_THROWS_AS(load_checkpoint_for(path, 0xABCDEF0123456789ull, 7), ConfigError);
}
