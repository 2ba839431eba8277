// The in-repo real sample (datasets/real-sample): its README lists every scan with its
// sha256, and it is a genuine excerpt of the large data in ../shared/data/real: scans byte for
// byte, nuScenes table records unchanged, KITTI text files unchanged or cut after the sample's
// last frame. The comparisons with the large data run when it is present (required under CI).
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <utility>

#include "core/config.hpp"
#include "support/real_data.hpp"
#include "support/sha256.hpp"

using namespace sgnlf;
namespace fs = std::filesystem;

namespace {

// "<64 hex>  <path relative to datasets/real-sample>" lines of the README (sha256sum's format).
std::map<std::string, std::string> listed_scans() {
  std::ifstream f(test::real_sample_root() + "/README.md");
  REQUIRE(f.good());
  std::map<std::string, std::string> m;
  for (std::string l; std::getline(f, l);) {
    if (l.size() < 67 || l.compare(64, 2, "  ") != 0) continue;
    if (l.find_first_not_of("0123456789abcdef") != 64) continue;
    m[l.substr(66)] = l.substr(0, 64);
  }
  return m;
}

std::set<std::string> sample_scan_files() {
  std::set<std::string> s;
  const fs::path root = test::real_sample_root();
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    const std::string n = e.path().filename().string();
    if (e.is_regular_file() && n.size() > 4 && n.compare(n.size() - 4, 4, ".bin") == 0)
      s.insert(fs::relative(e.path(), root).generic_string());
  }
  return s;
}

std::vector<std::string> lines(const std::string& path) {
  std::ifstream f(path);
  INFO(path);
  REQUIRE(f.good());
  std::vector<std::string> v;
  for (std::string l; std::getline(f, l);) v.push_back(l);
  return v;
}

// The sample's lines are the first lines of the large file's.
void check_prefix(const std::string& sample, const std::string& full, size_t n) {
  INFO(sample << " vs " << full);
  const auto a = lines(sample), b = lines(full);
  REQUIRE(a.size() == n);
  REQUIRE(b.size() >= n);
  CHECK(std::equal(a.begin(), a.end(), b.begin()));
}

}  // namespace

TEST_CASE("sha256 of the FIPS 180-4 examples", "[real_sample]") {
  auto bytes = [](const std::string& s) { return std::vector<uint8_t>(s.begin(), s.end()); };
  CHECK(test::sha256_hex({}) == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  CHECK(test::sha256_hex(bytes("abc")) ==
        "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  // 56 bytes: the padding spills into a second block.
  CHECK(test::sha256_hex(bytes("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq")) ==
        "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  CHECK(test::sha256_hex(std::vector<uint8_t>(1000000, uint8_t('a'))) ==
        "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST_CASE("the in-repo real sample: every scan listed in its README, with its sha256 and licence",
          "[real_sample]") {
  const auto listed = listed_scans();
  const auto files = sample_scan_files();
  CHECK(files.size() == 5);  // KITTI 000046-000047, the nuScenes single, scene-0916's first 2
  std::set<std::string> names;
  for (const auto& [path, sha] : listed) names.insert(path);
  CHECK(names == files);
  for (const auto& [path, sha] : listed) {
    INFO(path);
    CHECK(test::sha256_file(test::real_sample_root() + "/" + path) == sha);
  }
  const auto readme = lines(test::real_sample_root() + "/README.md");
  auto mentions = [&](const std::string& s) {
    return std::any_of(readme.begin(), readme.end(),
                       [&](const std::string& l) { return l.find(s) != std::string::npos; });
  };
  CHECK(mentions("CC BY-NC-SA 3.0"));
  CHECK(mentions("CC BY-NC-SA 4.0"));
  const std::string terms = "/nuscenes-mini-scene-0916/nuScenes_TERMS_OF_USE.txt";
  CHECK(fs::file_size(test::real_sample_root() + terms) > 20000);
}

TEST_CASE("the in-repo real sample's scans are byte-identical to the large real data",
          "[real][real_sample]") {
  for (const auto& [path, sha] : listed_scans()) {
    const std::string top = path.substr(0, path.find('/'));
    const test::RealData r = test::full_real_data(top, "the larger data to compare the sample with");
    if (!r) return;
    INFO(path);
    CHECK(test::sha256_file(r.path + path.substr(top.size())) == sha);
  }
}

TEST_CASE("the in-repo real sample's text files and nuScenes records are the large data's",
          "[real][real_sample]") {
  const std::string s = test::real_sample_root();
  const std::string why = "the larger data to compare the in-repo sample with";
  const auto k = test::full_real_data("kitti-odometry-00-slice", why);
  const auto n = test::full_real_data("nuscenes-mini-scene-0916", why);
  if (!k || !n) return;
  // KITTI: calib.txt as is; times and poses (line i = frame i) up to the last frame, 47.
  CHECK(lines(s + "/kitti-odometry-00-slice/sequences/00/calib.txt") ==
        lines(k.path + "/sequences/00/calib.txt"));
  check_prefix(s + "/kitti-odometry-00-slice/sequences/00/times.txt", k.path + "/sequences/00/times.txt", 48);
  check_prefix(s + "/kitti-odometry-00-slice/poses/00.txt", k.path + "/poses/00.txt", 48);
  // nuScenes: every record of every table is the large table's record of the same token.
  const std::string ns = s + "/nuscenes-mini-scene-0916";
  for (const char* t : {"scene", "sample", "sample_data", "ego_pose", "calibrated_sensor", "sensor"}) {
    INFO(t);
    const Json a = load_json_file(ns + "/v1.0-mini/" + t + ".json");
    const Json b = load_json_file(n.path + "/v1.0-mini/" + t + ".json");
    REQUIRE(a.is_array());
    CHECK_FALSE(a.empty());
    for (const Json& rec : a) {
      const auto it =
          std::find_if(b.begin(), b.end(), [&](const Json& x) { return x["token"] == rec["token"]; });
      REQUIRE(it != b.end());
      CHECK(*it == rec);
    }
  }
  // The sample_data records are the scene's first 2 keyframes in time, one a scan file.
  const Json sd = load_json_file(ns + "/v1.0-mini/sample_data.json");
  std::vector<std::pair<int64_t, std::string>> keys;
  for (const Json& rec : load_json_file(n.path + "/v1.0-mini/sample_data.json"))
    if (rec["is_key_frame"] == true)
      keys.emplace_back(rec["timestamp"].get<int64_t>(), rec["filename"].get<std::string>());
  std::sort(keys.begin(), keys.end());
  REQUIRE(sd.size() == 2);
  std::set<std::string> want = {keys.at(0).second, keys.at(1).second}, have;
  for (const Json& rec : sd) have.insert(rec["filename"].get<std::string>());
  CHECK(have == want);
  for (const auto& f : want) CHECK(fs::exists(ns + "/" + f));
  check_prefix(ns + "/times.txt", n.path + "/times.txt", 2);
  check_prefix(ns + "/reference_poses_lidar_world.txt", n.path + "/reference_poses_lidar_world.txt", 2);
  CHECK(lines(ns + "/nuScenes_TERMS_OF_USE.txt") == lines(n.path + "/nuScenes_TERMS_OF_USE.txt"));
}
