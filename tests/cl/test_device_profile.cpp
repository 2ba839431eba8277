// Device profiles (cl/device_profile.hpp): the built-in table (cpu = the launch shapes and
// kernels every run used before profiles), the choice by device type, the spec and
// SGNLF_DEVICE_PROFILE, strict JSON files (the MLP GEMM tiles' checks among them), and
// cl::launch_1d taking its work-group size from the Runtime's profile.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <fstream>

#include "cl/device_profile.hpp"
#include "cl/launch.hpp"
#include "cl/runtime.hpp"
#include "core/config.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;
using Catch::Matchers::Contains;

namespace {
std::string write_profile(const std::string& name, const std::string& text) {
  const std::string path = test::temp_dir("device_profile") + "/" + name;
  std::ofstream(path) << text;
  return path;
}
cl::DeviceInfo device_of_type(const std::string& type) {
  cl::DeviceInfo d;
  d.type = type;
  return d;
}
}  // namespace

TEST_CASE("built-in device profiles and the choice by device type", "[cl][device_profile]") {
  const auto cpu = cl::cpu_profile();  // today's shapes: any change moves every CPU result
  CHECK(cpu.name == "cpu");
  CHECK(cpu.local_size == 64);
  CHECK(cpu.encoder_backward == cl::EncoderBackward::Serial);
  CHECK(cpu.hash_grid_chunk == 256);
  CHECK(cpu.plane_chunk == 64);
  CHECK(cpu.gemm == cl::GemmVariant::CpuTiles);
  CHECK(cpu.compaction == cl::CompactionScan::Host);
  CHECK(cpu.pose_grad == cl::PoseGrad::Host);
  CHECK(cpu.loss_reduce == cl::LossReduce::Host);
  CHECK(cpu.chamfer == cl::ChamferSearch::Host);
  CHECK(cpu.ray_work_items == 1);
  CHECK(cpu.radix_tile == 256);
  CHECK(cpu.radix_min_work_items == 0);
  const auto gpu = cl::gpu_profile();
  CHECK(gpu.name == "gpu");
  CHECK(gpu.local_size == 64);
  CHECK(gpu.encoder_backward == cl::EncoderBackward::DeterministicParallel);
  CHECK(gpu.hash_grid_chunk == 1);
  CHECK(gpu.plane_chunk == 1);
  CHECK(gpu.gemm == cl::GemmVariant::LocalTiles);
  CHECK(gpu.gemm_block_rows * gpu.gemm_block_cols <= 32);
  CHECK(gpu.compaction == cl::CompactionScan::Device);
  CHECK(gpu.pose_grad == cl::PoseGrad::Device);
  CHECK(gpu.loss_reduce == cl::LossReduce::Device);
  CHECK(gpu.chamfer == cl::ChamferSearch::Device);
  CHECK(gpu.ray_work_items == 32);
  CHECK(gpu.radix_tile == 256);
  CHECK(gpu.radix_min_work_items == 16384);
  CHECK(cl::automatic_profile(device_of_type("CPU")) == cpu);
  CHECK(cl::automatic_profile(device_of_type("GPU")) == gpu);
  CHECK(cl::automatic_profile(device_of_type("accelerator")) == gpu);
  const auto cpu_dev = device_of_type("CPU");
  CHECK(cl::resolve_profile("gpu", cpu_dev) == gpu);
  CHECK(cl::resolve_profile("cpu", device_of_type("GPU")) == cpu);
  CHECK(cl::resolve_profile("auto", device_of_type("GPU")) == gpu);
  CHECK(gpu.to_json()["encoder_backward"] == "deterministic_parallel");
  CHECK(gpu.to_json()["gemm"] == "local_tiles");
  CHECK(cpu.to_json()["gemm"] == "cpu_tiles");
  CHECK(gpu.to_json()["compaction"] == "device");
  CHECK(cpu.to_json()["compaction"] == "host");
  CHECK(gpu.to_json()["pose_grad"] == "device");
  CHECK(cpu.to_json()["pose_grad"] == "host");
  CHECK(gpu.to_json()["loss_reduce"] == "device");
  CHECK(cpu.to_json()["loss_reduce"] == "host");
  CHECK(gpu.to_json()["chamfer"] == "device");
  CHECK(cpu.to_json()["chamfer"] == "host");
  CHECK(cl::DeviceProfile::from_json(gpu.to_json(), "p", cpu) == gpu);
}

TEST_CASE("SGNLF_DEVICE_PROFILE is the default spec", "[cl][device_profile]") {
  const char* old = std::getenv("SGNLF_DEVICE_PROFILE");
  const std::string saved = old ? old : "";
  ::setenv("SGNLF_DEVICE_PROFILE", "gpu", 1);
  CHECK(cl::default_profile_spec() == "gpu");
  CHECK(cl::resolve_profile("", device_of_type("CPU")).name == "gpu");
  CHECK(cl::resolve_profile("cpu", device_of_type("CPU")).name == "cpu");  // explicit wins
  ::unsetenv("SGNLF_DEVICE_PROFILE");
  CHECK(cl::default_profile_spec() == "auto");
  CHECK(cl::resolve_profile("", device_of_type("CPU")).name == "cpu");
  if (old) ::setenv("SGNLF_DEVICE_PROFILE", saved.c_str(), 1);
}

TEST_CASE("device profile files: keys over a base, strictly read", "[cl][device_profile]") {
  const auto cpu_dev = device_of_type("CPU");
  const auto p = cl::resolve_profile(
      write_profile("atomic.json",
                    R"({"name": "h200-atomic", "base": "gpu", "encoder_backward": "atomic",
                        "local_size": 128})"),
      cpu_dev);
  CHECK(p.name == "h200-atomic");
  CHECK(p.encoder_backward == cl::EncoderBackward::Atomic);
  CHECK(p.local_size == 128);
  CHECK(p.plane_chunk == 1);  // from the base
  // Without a base: the device's automatic profile.
  CHECK(cl::resolve_profile(write_profile("wide.json", R"({"name": "wide", "local_size": 32})"),
                            cpu_dev)
            .hash_grid_chunk == 256);
  CHECK_THROWS_WITH(
      cl::resolve_profile(write_profile("typo.json", R"({"name": "t", "local_sise": 32})"),
                          cpu_dev),
      Contains("local_sise") && Contains("local_size"));
  CHECK_THROWS_WITH(
      cl::resolve_profile(write_profile("bad.json", R"({"name": "b", "encoder_backward": "fast"})"),
                          cpu_dev),
      Contains("encoder_backward") && Contains("deterministic_parallel"));
  CHECK_THROWS_WITH(
      cl::resolve_profile(write_profile("zero.json", R"({"name": "z", "local_size": 0})"), cpu_dev),
      Contains("local_size") && Contains("0"));
  CHECK_THROWS_WITH(
      cl::resolve_profile(write_profile("base.json", R"({"name": "b", "base": "tpu"})"), cpu_dev),
      Contains("'base' = 'tpu'"));
  CHECK_THROWS_WITH(cl::resolve_profile(write_profile("anon.json", R"({"local_size": 32})"),
                                        cpu_dev),
                    Contains("needs a 'name'"));
  CHECK_THROWS_WITH(cl::resolve_profile("/no/such/profile.json", cpu_dev),
                    Contains("/no/such/profile.json") && Contains("auto, cpu, gpu"));
  CHECK_THROWS_AS(cl::resolve_profile("fast", cpu_dev), ConfigError);
  // The GEMM tiles: a GPU's file may retune them; shapes the kernels cannot take are refused.
  const auto tuned = cl::resolve_profile(
      write_profile("tiles.json", R"({"name": "t", "base": "gpu", "gemm_tile": 32,
                                      "gemm_block_rows": 8, "gemm_block_cols": 4})"),
      cpu_dev);
  CHECK(tuned.gemm == cl::GemmVariant::LocalTiles);
  CHECK(tuned.gemm_tile == 32);
  CHECK(tuned.gemm_block_rows == 8);
  CHECK(cl::resolve_profile(write_profile("cpu_gemm.json",
                                          R"({"name": "g", "base": "gpu", "gemm": "cpu_tiles"})"),
                            cpu_dev)
            .gemm == cl::GemmVariant::CpuTiles);
  CHECK(cl::resolve_profile(write_profile("host_scan.json",
                                          R"({"name": "g", "base": "gpu", "compaction": "host"})"),
                            cpu_dev)
            .compaction == cl::CompactionScan::Host);
  CHECK(cl::resolve_profile(write_profile("host_pose.json",
                                          R"({"name": "g", "base": "gpu", "pose_grad": "host"})"),
                            cpu_dev)
            .pose_grad == cl::PoseGrad::Host);
  CHECK_THROWS_WITH(
      cl::resolve_profile(write_profile("rwi.json", R"({"name": "r", "ray_work_items": 24})"),
                          cpu_dev),
      Contains("ray_work_items") && Contains("power of two"));
  CHECK_THROWS_WITH(cl::resolve_profile(write_profile("rwi_big.json",
                                                      R"({"name": "r", "local_size": 32, "ray_work_items": 64})"),
                                        cpu_dev),
                    Contains("ray_work_items") && Contains("local_size"));
  CHECK_THROWS_WITH(
      cl::resolve_profile(write_profile("tile.json", R"({"name": "t", "radix_tile": 0})"), cpu_dev),
      Contains("radix_tile"));
  CHECK_THROWS_WITH(
      cl::resolve_profile(write_profile("loss.json", R"({"name": "l", "loss_reduce": "gpu"})"),
                          cpu_dev),
      Contains("loss_reduce") && Contains("device"));
  CHECK_THROWS_WITH(
      cl::resolve_profile(write_profile("chamfer.json", R"({"name": "c", "chamfer": "kdtree"})"),
                          cpu_dev),
      Contains("chamfer") && Contains("kdtree") && Contains("device"));
  CHECK_THROWS_WITH(
      cl::resolve_profile(write_profile("pose.json", R"({"name": "p", "pose_grad": "gpu"})"),
                          cpu_dev),
      Contains("pose_grad") && Contains("device"));
  CHECK_THROWS_WITH(
      cl::resolve_profile(write_profile("scan.json", R"({"name": "s", "compaction": "gpu"})"),
                          cpu_dev),
      Contains("compaction") && Contains("device"));
  CHECK_THROWS_WITH(
      cl::resolve_profile(write_profile("gemm.json", R"({"name": "g", "gemm": "tensor_cores"})"),
                          cpu_dev),
      Contains("gemm") && Contains("local_tiles"));
  CHECK_THROWS_WITH(
      cl::resolve_profile(write_profile("tile.json", R"({"name": "t", "gemm_tile": 40})"), cpu_dev),
      Contains("gemm_tile") && Contains("multiple of 16"));
  CHECK_THROWS_WITH(
      cl::resolve_profile(write_profile("block.json",
                                        R"({"name": "b", "gemm_block_rows": 8, "gemm_block_cols": 8})"),
                          cpu_dev),
      Contains("64 floats") && Contains("more than 32"));
  CHECK_THROWS_WITH(
      cl::resolve_profile(write_profile("cols.json", R"({"name": "c", "gemm_block_cols": 3})"),
                          cpu_dev),
      Contains("gemm_block_cols") && Contains("divide 16"));
  CHECK_THROWS_WITH(
      cl::resolve_profile(write_profile("wg.json",
                                        R"({"name": "w", "gemm_work_group": 16, "gemm_block_cols": 1})"),
                          cpu_dev),
      Contains("gemm_work_group"));
}

TEST_CASE("launch_1d takes the work-group size of the Runtime's profile", "[cl][device_profile]") {
  auto& rt = test::runtime();
  const cl::DeviceProfile saved = rt.device_profile();
  const std::string src =
      "__kernel void local_size(const int n, __global int* out) {\n"
      "  const int i = get_global_id(0);\n"
      "  if (i < n) out[i] = (int)get_local_size(0) * 1000 + (int)get_global_size(0);\n"
      "}\n";
  cl::Kernel k(rt, rt.program_from_source(src, "", "local_size.cl"), "local_size");
  cl::Buffer out(rt, 100 * sizeof(int));
  k.set_args(100, out);
  cl::launch_1d(k, 100);
  const int ls = saved.local_size;
  CHECK(out.read_vec<int>(100)[99] == ls * 1000 + int(cl::round_up(100, size_t(ls))));
  cl::DeviceProfile p = saved;
  p.local_size = 32;
  rt.set_device_profile(p);
  cl::launch_1d(k, 100);
  const auto v = out.read_vec<int>(100);
  rt.set_device_profile(saved);
  CHECK(v[0] == 32 * 1000 + 128);
  p.local_size = 0;
  CHECK_THROWS_AS(rt.set_device_profile(p), ConfigError);
  CHECK(rt.device_profile() == saved);
}
