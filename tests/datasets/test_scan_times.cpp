// Scan times of a plain folder (scan_times.hpp): from a times.txt (bad counts and values refused
// naming the file and line), else from timestamps in every file name (ns, μs, ms, s, s.fraction),
// else none; and the genuine nuScenes scans copied into a plain folder: the same times as the
// nuScenes layout gives them, the low-frequency class, no reference poses; converted to PCD
// and to PLY with their raw intensities, the same bits as the .pcd.bin folder.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <cstring>
#include <fstream>

#include "core/error.hpp"
#include "datasets/loader.hpp"
#include "datasets/scan_times.hpp"
#include "io/cloud_writers.hpp"
#include "support/real_data.hpp"
#include "support/test_device.hpp"

using namespace sgnlf;
namespace fs = std::filesystem;

TEST_CASE("timestamps in scan file names", "[datasets][scan-times]") {
  CHECK(*timestamp_from_file_name("a/n015__LIDAR_TOP__1538984233547259.pcd.bin") ==
        double(1538984233547259LL) * 1e-6);
  CHECK(*timestamp_from_file_name("1538984233547259123.pcd") == Approx(1538984233.547259123));
  CHECK(*timestamp_from_file_name("scan_1538984233547.ply") == Approx(1538984233.547));
  CHECK(*timestamp_from_file_name("1538984233.bin") == 1538984233.0);
  CHECK(*timestamp_from_file_name("cloud_1538984233.547259.pcd") == Approx(1538984233.547259));
  CHECK_FALSE(timestamp_from_file_name("000042.bin"));      // a frame number
  CHECK_FALSE(timestamp_from_file_name("scan.pcd"));
  CHECK_FALSE(timestamp_from_file_name("12345678901.bin"));  // 11 digits: no known unit
}

TEST_CASE("scan_times: times.txt first, then the names, else none", "[datasets][scan-times]") {
  const fs::path dir = test::temp_dir("scan_times");
  const std::vector<std::string> files = {(dir / "000000.bin").string(), (dir / "000001.bin").string(),
                                          (dir / "000002.bin").string()};
  CHECK_FALSE(scan_times(dir.string(), files));  // frame numbers: no times
  {
    std::ofstream(dir / "times.txt") << "0.0\n0.5\n1.0\n";
  }
  auto t = scan_times(dir.string(), files);
  REQUIRE(t);
  CHECK(t->source == "times.txt");
  CHECK(t->rate_hz() == Approx(2.0));
  {
    std::ofstream(dir / "times.txt") << "0.0\n0.5\n";
  }
  CHECK_THROWS_WITH(scan_times(dir.string(), files), Catch::Contains("times.txt") && Catch::Contains("2 times for 3"));
  {
    std::ofstream(dir / "times.txt") << "0.0\n0.5\n0.4\n";
  }
  CHECK_THROWS_WITH(scan_times(dir.string(), files), Catch::Contains("times.txt:3"));
  {
    std::ofstream(dir / "times.txt") << "0.0\nabc\n1.0\n";
  }
  CHECK_THROWS_AS(scan_times(dir.string(), files), IoError);
  fs::remove(dir / "times.txt");
  const std::vector<std::string> named = {(dir / "s_1538984233000000.pcd").string(),
                                          (dir / "s_1538984233100000.pcd").string()};
  t = scan_times(dir.string(), named);
  REQUIRE(t);
  CHECK(t->source == "file names");
  CHECK(t->rate_hz() == Approx(10.0));
  // Names that do not increase are not times.
  CHECK_FALSE(scan_times(dir.string(), {named[1], named[0]}));
}

TEST_CASE("nuScenes scans in a plain folder keep the layout's times", "[datasets][scan-times][real]") {
  const test::RealData real = test::real_data("nuscenes-mini-scene-0916");
  if (!real) return;
  const fs::path plain = test::temp_dir("scan_times_nuscenes");
  std::vector<fs::path> scans;
  for (const auto& e : fs::directory_iterator(fs::path(real.path) / "samples" / "LIDAR_TOP"))
    scans.push_back(e.path());
  std::sort(scans.begin(), scans.end());
  for (const auto& p : scans) fs::copy_file(p, plain / p.filename());
  LoadOptions all;
  all.frames = int(scans.size());
  const Dataset layout = load_dataset(real.path, all);
  LoadOptions none;
  const Dataset folder = load_dataset(plain.string(), none);
  CHECK(layout.has_reference_poses);
  CHECK_FALSE(folder.has_reference_poses);
  CHECK(folder.frequency == "low");
  CHECK(folder.sensor.name == layout.sensor.name);
  REQUIRE(folder.frames.size() == layout.frames.size());
  for (size_t k = 0; k < folder.frames.size(); ++k) {
    CHECK(folder.frames[k].timestamp_s == layout.frames[k].timestamp_s);
    CHECK(folder.frames[k].points.size() == layout.frames[k].points.size());
  }
  CHECK(folder.split.test == layout.split.test);

  // The same scans as PCD and PLY files (their raw 0–255 intensities and rings, the names'
  // times kept)
  // load to the same bits: the folder's intensity scale is the nuScenes reader's 1/255.
  const fs::path pcd = test::temp_dir("scan_times_nuscenes_pcd");
  const fs::path ply = test::temp_dir("scan_times_nuscenes_ply");
  for (const auto& p : scans) {
    std::ifstream in(p, std::ios::binary);
    std::vector<float> rec((fs::file_size(p) / 20) * 5);
    in.read(reinterpret_cast<char*>(rec.data()), std::streamsize(rec.size() * sizeof(float)));
    std::vector<PointXYZI> pts;
    io::ScanExtras ex;
    ex.has_ring = true;
    for (size_t i = 0; i + 4 < rec.size(); i += 5) {
      pts.push_back({rec[i], rec[i + 1], rec[i + 2], rec[i + 3]});
      ex.ring.push_back(int32_t(rec[i + 4]));
    }
    std::string stem = p.filename().string();
    stem.resize(stem.size() - std::string(".pcd.bin").size());
    io::write_pcd((pcd / (stem + ".pcd")).string(), pts, io::PcdEncoding::kBinaryCompressed, &ex);
    io::write_ply((ply / (stem + ".ply")).string(), pts, io::PlyEncoding::kBinaryLittleEndian, &ex);
  }
  for (const fs::path& dir : {pcd, ply}) {
    const Dataset other = load_dataset(dir.string(), none);
    CHECK(other.sensor.name == folder.sensor.name);
    CHECK(other.frequency == "low");
    REQUIRE(other.frames.size() == folder.frames.size());
    bool same = true;
    for (size_t k = 0; k < other.frames.size(); ++k) {
      same = same && other.frames[k].timestamp_s == folder.frames[k].timestamp_s &&
             other.frames[k].points.size() == folder.frames[k].points.size() &&
             std::memcmp(other.frames[k].points.data(), folder.frames[k].points.data(),
                         other.frames[k].points.size() * sizeof(PointXYZI)) == 0 &&
             other.frames[k].image.range == folder.frames[k].image.range &&
             other.frames[k].image.intensity == folder.frames[k].image.intensity;
    }
    CHECK(same);
  }
}
