// Device profiles: the launch shapes and kernel variants a device runs, as one table.
//
// A profile names the work-group size of the element-wise kernels (cl::launch_1d), the
// variant of the encoders' parameter backward (hash grid, time hash grid, K-Planes), the
// points per work-item of the encoders' forward on CPUs and the variant and tiles of the MLP
// layers' GEMMs, and where the step's small reductions run (early termination's prefix sum,
// the pose gradient's sums, the loss).
// The built-in "cpu" profile is exactly what every run did before profiles
// existed (local size 64, the serial per-level backward, hash-grid chunks of 256 points, plane
// chunks of 64, the float16 register-tiled GEMMs of kernels/field/mlp.cl); "gpu" keeps local
// size 64, runs one point per work-item, the deterministic parallel backward (sorted by entry,
// summed in point order, bit-identical to the serial one: docs/opencl-layer.md), the
// local-memory tiled GEMMs of kernels/field/mlp_tiles.cl, compaction's scan, the pose
// gradient's sums and the loss's on the device.
// A device of type CPU gets "cpu", any other device (GPU, accelerator) "gpu"; the vendor is recorded in the result's context but
// chooses nothing yet. `--device-profile cpu|gpu|auto|FILE` (or SGNLF_DEVICE_PROFILE) overrides
// the choice; FILE is JSON whose keys are read over the built-in profile named by its "base"
// (default: the device's automatic one), unknown keys refused.
#pragma once
#include <string>

#include "cl/device.hpp"
#include "core/config_choices.hpp"
#include "core/config_fwd.hpp"

namespace sgnlf::cl {

// The encoders' parameter backward: serial = one work-item per level (or scale-group) owning its
// slice, summing over the points in order; atomic = one work-item per (point, level) with
// compare-and-swap float adds (order varies between runs); deterministic_parallel = the
// (entry, point) contributions sorted by entry (stable radix sort) and summed per entry in the
// serial order, one work-item per entry.
enum class EncoderBackward { Serial, Atomic, DeterministicParallel };

inline constexpr std::pair<EncoderBackward, const char*> kEncoderBackwardNames[] = {
    {EncoderBackward::Serial, "serial"},
    {EncoderBackward::Atomic, "atomic"},
    {EncoderBackward::DeterministicParallel, "deterministic_parallel"}};

const char* encoder_backward_name(EncoderBackward b);

// The MLP layers' GEMMs (field::Mlp): cpu_tiles = kernels/field/mlp.cl, each work-item 8 points
// x 16 outputs in float16 registers with no local memory (shaped for AVX-512 cores through
// PoCL); local_tiles = kernels/field/mlp_tiles.cl, work-groups that stage tiles of the inputs
// and weights in local memory and give each work-item a small register block (the gemm_* keys).
// The convolutions (conv::Conv2d) take the same key and tiles: cpu_tiles = kernels/conv/
// conv2d.cl and conv2d_narrow.cl, local_tiles = kernels/conv/conv2d_tiles.cl.
enum class GemmVariant { CpuTiles, LocalTiles };

inline constexpr std::pair<GemmVariant, const char*> kGemmNames[] = {
    {GemmVariant::CpuTiles, "cpu_tiles"}, {GemmVariant::LocalTiles, "local_tiles"}};

const char* gemm_name(GemmVariant g);

// Early ray termination's per-ray offsets (pipeline::SampleCompaction): host = the live counts
// read back, summed on the host and written back (two blocking transfers); device = a
// work-group scan on the device (kernels/common/scan.clh) and one blocking read of the total,
// which sizes the launches after it. Integer sums: the offsets are the same bits either way.
enum class CompactionScan { Host, Device };

inline constexpr std::pair<CompactionScan, const char*> kCompactionNames[] = {
    {CompactionScan::Host, "host"}, {CompactionScan::Device, "device"}};

const char* compaction_name(CompactionScan c);

// The pose-free methods' pose gradient (PoseFreeStep): host = the per-ray gradients read back
// (3 × n_rays × 3 floats) and summed in double on the host (render::pose_gradient); device = the
// same sums in float on the device in a fixed tree (kernels/render/pose_grad.cl), 6 floats read
// back, the Jacobians and the pose Adam on the host. Bit-reproducible per device either way;
// the two differ by the sums' float rounding.
enum class PoseGrad { Host, Device };

inline constexpr std::pair<PoseGrad, const char*> kPoseGradNames[] = {
    {PoseGrad::Host, "host"}, {PoseGrad::Device, "device"}};

const char* pose_grad_name(PoseGrad g);

// Where weight carving's per-ray loss terms are summed (the loss the pose-free step's
// reweighting and the logged steps read, LidarNerfModel::read_losses: the loss buffer read once
// either way): host = read back and summed in double on the host; device = summed on the device
// in the loss kernels' fixed tree (render_loss_reduce) into the loss buffer.
enum class LossReduce { Host, Device };

inline constexpr std::pair<LossReduce, const char*> kLossReduceNames[] = {
    {LossReduce::Host, "host"}, {LossReduce::Device, "device"}};

const char* loss_reduce_name(LossReduce l);

// LiDAR4D's Chamfer losses (the ray term's and the flow supervision's): host = the predicted
// points and the flow read back, nearest neighbours by geometry::KdTree on the host, the
// gradients written back (3 + 4 blocking transfers a step); device = brute-force nearest
// neighbours in local-memory tiles, the gradients and the losses' fixed-tree sums on the device
// (kernels/render/chamfer.cl), the values read only when asked (logged steps).
enum class ChamferSearch { Host, Device };

inline constexpr std::pair<ChamferSearch, const char*> kChamferNames[] = {
    {ChamferSearch::Host, "host"}, {ChamferSearch::Device, "device"}};

const char* chamfer_name(ChamferSearch c);

struct DeviceProfile {
  std::string name = "cpu";
  // Work-group size of the 1-D element-wise kernels (global size rounded up to it).
  int local_size = 64;
  EncoderBackward encoder_backward = EncoderBackward::Serial;
  // Points per work-item of the hash grid's forward and d_x under schedule "auto"
  // (kernels/field/hashgrid.cl CHUNK; 1 = the per-point kernels).
  int hash_grid_chunk = 256;
  // Points per work-item of the time hash grid's and K-Planes' forward when their config's
  // chunk is 0 (1 = one point per work-item, work-groups of 64).
  int plane_chunk = 64;
  // The MLP GEMMs' variant; the gemm_* keys below shape local_tiles only (kernels/field/
  // mlp_tiles.cl, runtime/field/mlp.cpp; cpu_tiles' shapes are fixed in mlp.cpp).
  GemmVariant gemm = GemmVariant::CpuTiles;
  // Work-items per work-group at most (a layer narrower than a tile gets fewer).
  int gemm_work_group = 256;
  // Columns of a work-group's output tile (the layer's outputs, d_in's inputs or the weight
  // gradient's columns), a multiple of 16; a narrower layer's tile is its padded width.
  int gemm_tile = 64;
  // Depth of a local-memory tile: inputs (forward), outputs (d_in) or points (weight gradient).
  int gemm_tile_k = 16;
  // Register block of a work-item: rows (points; weight rows in the weight gradient) x columns,
  // at most 32 floats; columns divide 16.
  int gemm_block_rows = 4;
  int gemm_block_cols = 4;
  // A launch that the block above would give fewer work-items than this runs with a 1 x 1 block
  // and 16-column tiles instead (small batches: the flow MLP, per-ray inputs). Every sum keeps
  // its order, so the results are the same.
  int gemm_min_work_items = 16384;
  // Weight gradient: chunks of at least gemm_chunk_points points, at most gemm_max_chunks of
  // them, each summed in point order, then the chunks summed in a fixed tree: for a given N the
  // chunking, and so the rounding, is fixed.
  int gemm_chunk_points = 64;
  int gemm_max_chunks = 1024;
  // Where early termination's prefix sum runs (above).
  CompactionScan compaction = CompactionScan::Host;
  // Where the pose gradient's per-ray sums run (above).
  PoseGrad pose_grad = PoseGrad::Host;
  // How the loss is summed and read (above).
  LossReduce loss_reduce = LossReduce::Host;
  // Where LiDAR4D's Chamfer losses run (above).
  ChamferSearch chamfer = ChamferSearch::Host;
  // Work-items that share one ray in the per-ray render, sampling and compaction kernels
  // (volume rendering's sums and their backward, the ray-gradient reduction, weight carving,
  // importance and surface sampling, early termination's counts): 1 = one work-item walks the
  // ray's samples in order (the cpu profile's kernels); a power of two above 1 = a work-group
  // slice of that many work-items per ray that splits the samples and combines them with
  // local-memory scans and fixed-tree sums (deterministic per device, not the cpu kernels' bits).
  // Above 1 it also selects the other per-ray or per-point loops' per-element kernels: the
  // direction encoding's (a work-item per (ray, frequency)) and the scene flow's time
  // interpolation (one per output word).
  int ray_work_items = 1;
  // Pairs per work-item of the deterministic parallel backward's radix sort (entry_radix_hist
  // and entry_radix_scatter, kernels/field/entry_reduce.cl RADIX_TILE): each work-item counts
  // and then scatters one tile of a unit's pairs in order; the histogram (16 words a tile) is
  // scanned per unit. radix_tile is the largest tile; a sort whose tiles
  // would give fewer than radix_min_work_items work-items halves its tile until they do (or
  // the tile is 1). cpu: 256 and 0 (always 256); gpu: 256 and 16 384, so that the big sorts
  // (the hash grid's millions of pairs) keep 256 and a small histogram while LiDAR4D's time hash
  // grid, K-Planes and scene flow sorts (1.5-2.6e5 pairs) get 16384-18432 work-items instead
  // of 576-1024. The sort is stable at any tile: the same order and gradient bits. Above 0 the
  // scan too runs in blocks of 64 work-items, enough for radix_min_work_items (field::RadixScan:
  // reduce-then-scan; at 0 one work-group per unit); integer sums, the same words either way.
  int radix_tile = 256;
  int radix_min_work_items = 0;

  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("name", s.name);
    v("local_size", s.local_size, 1, 1024);
    v("encoder_backward", s.encoder_backward, config::choices(kEncoderBackwardNames));
    v("hash_grid_chunk", s.hash_grid_chunk, 1, 65536);
    v("plane_chunk", s.plane_chunk, 1, 65536);
    v("gemm", s.gemm, config::choices(kGemmNames));
    v("gemm_work_group", s.gemm_work_group, 16, 1024);
    v("gemm_tile", s.gemm_tile, 16, 128);
    v("gemm_tile_k", s.gemm_tile_k, 1, 64);
    v("gemm_block_rows", s.gemm_block_rows, 1, 32);
    v("gemm_block_cols", s.gemm_block_cols, 1, 16);
    v("gemm_min_work_items", s.gemm_min_work_items, 0, 1 << 30);
    v("gemm_chunk_points", s.gemm_chunk_points, 1, 1 << 20);
    v("gemm_max_chunks", s.gemm_max_chunks, 1, 65536);
    v("compaction", s.compaction, config::choices(kCompactionNames));
    v("pose_grad", s.pose_grad, config::choices(kPoseGradNames));
    v("loss_reduce", s.loss_reduce, config::choices(kLossReduceNames));
    v("chamfer", s.chamfer, config::choices(kChamferNames));
    v("ray_work_items", s.ray_work_items, 1, 256);
    v("radix_tile", s.radix_tile, 1, 4096);
    v("radix_min_work_items", s.radix_min_work_items, 0, 1 << 30);
  }
  // Throws ConfigError naming `where` and the key.
  void validate(const std::string& where = "device_profile") const;
  Json to_json() const;
  // Strict: unknown keys refused. `base` is the profile the keys are read over (a "base" key in
  // the JSON, "cpu" or "gpu", replaces it).
  static DeviceProfile from_json(const Json& j, const std::string& where,
                                 const DeviceProfile& base);
  bool operator==(const DeviceProfile& o) const;
};

DeviceProfile cpu_profile();
DeviceProfile gpu_profile();
// "cpu" for a device of type CPU, "gpu" for any other.
DeviceProfile automatic_profile(const DeviceInfo& device);
// spec "" = default_profile_spec(); "auto" = automatic_profile(device); "cpu", "gpu"; anything
// else is the path of a JSON profile file. Throws ConfigError naming the spec or the file.
DeviceProfile resolve_profile(const std::string& spec, const DeviceInfo& device);
// The spec in effect when none is given explicitly (SGNLF_DEVICE_PROFILE or "auto").
std::string default_profile_spec();

}  // namespace sgnlf::cl
