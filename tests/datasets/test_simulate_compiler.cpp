// The simulator gives the same data for a seed whatever the compiler and optimisation level:
// the points and poses of two short sequences hash to the values the GCC -O3 build gave when
// every committed result was made. The ordinary suite (GCC) and CI's sanitizer job (Clang -O1,
// ASan+UBSan) both run this test. It failed in the Clang build before the draws inside argument
// lists were taken apart (runtime/datasets/sim_street.cpp): Clang evaluates a call's arguments
// first to last, GCC last to first, so a Clang build simulated another street from the same seed.
#include <catch2/catch.hpp>

#include <cstdio>
#include <string>

#include "core/config.hpp"
#include "datasets/simulate.hpp"

using namespace sgnlf;

namespace {

// FNV-1a over the bytes of every point (x, y, z, intensity as float) and every pose (double).
uint64_t dataset_hash(const Dataset& d) {
  uint64_t h = fnv1a64("");
  for (const auto& f : d.frames) {
    h = fnv1a64(std::string(reinterpret_cast<const char*>(f.points.data()),
                            f.points.size() * sizeof(PointXYZI)),
                h);
    const Eigen::Matrix4d T = f.T_world_lidar.matrix();
    h = fnv1a64(std::string(reinterpret_cast<const char*>(T.data()), sizeof(double) * 16), h);
    // Moving actors' labels (none in the static sequences: their hashes are as before).
    if (!f.labels.empty())
      h = fnv1a64(std::string(reinterpret_cast<const char*>(f.labels.data()), f.labels.size() * sizeof(uint16_t)), h);
  }
  return h;
}

std::string hex(uint64_t v) {
  char b[24];
  std::snprintf(b, sizeof b, "%016llx", static_cast<unsigned long long>(v));
  return b;
}

}  // namespace

TEST_CASE("the simulator's output does not depend on the compiler", "[datasets][simulate]") {
  struct Case {
    const char* sequence;
    int frames, width;
    const char* beams;
    const char* expected;  // GCC 12 -O3 (the build of every committed result)
  };
  const Case cases[] = {
      {"kitti360-low-a", 3, 360, "grid", "9ca81befd098744f"},
      {"nuscenes-low-a", 2, 256, "native", "bc834ce40842f5a1"},
      // The moving actors' draws (Rng stream 6) and their labels.
      {"kitti360-dyn-8120", 3, 360, "grid", "d3fb86ea7fcade21"},
  };
  for (const Case& c : cases) {
    SimOptions o;
    o.sequence = c.sequence;
    o.frames = c.frames;
    o.width = c.width;
    o.lidar.beams = c.beams;
    o.threads = 2;
    const Dataset d = simulate_dataset(o);
    size_t points = 0, on_actors = 0;
    for (const auto& f : d.frames) {
      points += f.points.size();
      for (uint16_t l : f.labels) on_actors += l != 0;
    }
    if (std::string(c.sequence).find("-dyn-") != std::string::npos) CHECK(on_actors > 100);
    INFO(c.sequence << ": " << d.frames.size() << " frames, " << points << " points");
    CHECK(points > 1000);
    CHECK(hex(dataset_hash(d)) == c.expected);
  }
}
