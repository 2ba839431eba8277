// DeviceProfile (device_profile.hpp): the built-in table, JSON reading and the choice per device.
#include "cl/device_profile.hpp"

#include <cstdlib>
#include <fstream>

#include "core/config.hpp"
#include "core/config_fields.hpp"
#include "core/error.hpp"

namespace sgnlf::cl {

const char* encoder_backward_name(EncoderBackward b) {
  return config::choices(kEncoderBackwardNames).name_of(b);
}

const char* gemm_name(GemmVariant g) { return config::choices(kGemmNames).name_of(g); }

const char* compaction_name(CompactionScan c) {
  return config::choices(kCompactionNames).name_of(c);
}

const char* pose_grad_name(PoseGrad g) { return config::choices(kPoseGradNames).name_of(g); }

const char* loss_reduce_name(LossReduce l) {
  return config::choices(kLossReduceNames).name_of(l);
}

const char* chamfer_name(ChamferSearch c) { return config::choices(kChamferNames).name_of(c); }

void DeviceProfile::validate(const std::string& where) const {
  if (name.empty()) throw ConfigError(where + ": 'name' must not be empty");
  config::check_fields(*this, where);
  if (gemm_tile % 16 != 0)
    throw ConfigError(where + ": 'gemm_tile' = " + std::to_string(gemm_tile) +
                      " must be a multiple of 16");
  if (16 % gemm_block_cols != 0)
    throw ConfigError(where + ": 'gemm_block_cols' = " + std::to_string(gemm_block_cols) +
                      " must divide 16 (1, 2, 4, 8 or 16)");
  if (gemm_block_rows * gemm_block_cols > 32)
    throw ConfigError(where + ": 'gemm_block_rows' x 'gemm_block_cols' = " +
                      std::to_string(gemm_block_rows * gemm_block_cols) +
                      " floats of registers per work-item, more than 32");
  if ((ray_work_items & (ray_work_items - 1)) != 0 || ray_work_items > local_size)
    throw ConfigError(where + ": 'ray_work_items' = " + std::to_string(ray_work_items) +
                      " must be a power of two no larger than 'local_size' = " +
                      std::to_string(local_size));
  if (gemm_work_group < gemm_tile / gemm_block_cols)
    throw ConfigError(where + ": 'gemm_work_group' = " + std::to_string(gemm_work_group) +
                      " is below a tile row of gemm_tile / gemm_block_cols = " +
                      std::to_string(gemm_tile / gemm_block_cols) + " work-items");
}

Json DeviceProfile::to_json() const { return config::write_fields(*this); }

bool DeviceProfile::operator==(const DeviceProfile& o) const { return to_json() == o.to_json(); }

DeviceProfile cpu_profile() { return DeviceProfile{}; }

DeviceProfile gpu_profile() {
  DeviceProfile p;
  p.name = "gpu";
  p.local_size = 64;
  p.encoder_backward = EncoderBackward::DeterministicParallel;
  p.hash_grid_chunk = 1;
  p.plane_chunk = 1;
  p.gemm = GemmVariant::LocalTiles;
  p.compaction = CompactionScan::Device;
  p.pose_grad = PoseGrad::Device;
  p.loss_reduce = LossReduce::Device;
  p.chamfer = ChamferSearch::Device;
  p.ray_work_items = 32;
  p.radix_min_work_items = 16384;
  return p;
}

DeviceProfile automatic_profile(const DeviceInfo& device) {
  return device.type == "CPU" ? cpu_profile() : gpu_profile();
}

namespace {
DeviceProfile builtin(const std::string& name, const std::string& where) {
  if (name == "cpu") return cpu_profile();
  if (name == "gpu") return gpu_profile();
  throw ConfigError(where + ": 'base' = '" + name + "' is not cpu or gpu");
}
}  // namespace

DeviceProfile DeviceProfile::from_json(const Json& j, const std::string& where,
                                       const DeviceProfile& base) {
  if (!j.is_object()) throw ConfigError(where + ": a device profile must be a JSON object");
  ConfigReader r(j, where);
  DeviceProfile p = base;
  if (r.has("base")) {
    std::string b;
    r.get("base", b);
    p = builtin(b, where);
  }
  config::read_fields_here(r, p);
  r.finish();
  p.validate(where);
  return p;
}

std::string default_profile_spec() {
  const char* e = std::getenv("SGNLF_DEVICE_PROFILE");
  return e && *e ? std::string(e) : std::string("auto");
}

DeviceProfile resolve_profile(const std::string& spec_in, const DeviceInfo& device) {
  const std::string spec = spec_in.empty() ? default_profile_spec() : spec_in;
  if (spec == "auto") return automatic_profile(device);
  if (spec == "cpu") return cpu_profile();
  if (spec == "gpu") return gpu_profile();
  if (!std::ifstream(spec))
    throw ConfigError("device profile '" + spec +
                      "' is not auto, cpu, gpu or a readable JSON file");
  const Json j = load_config_file(spec);
  DeviceProfile p = DeviceProfile::from_json(j, spec, automatic_profile(device));
  if (!j.contains("name"))
    throw ConfigError(spec + ": a device profile file needs a 'name' (it is recorded in results)");
  return p;
}

}  // namespace sgnlf::cl
