#include "harness/roofline.hpp"

#include <algorithm>
#include <cmath>

#include "core/config.hpp"
#include "harness/stats.hpp"

namespace sgnlf::harness {

RooflineProbe::RooflineProbe(cl::Runtime& rt)
    : rt_(rt),
      fma_(rt.kernel("roofline/roofline.cl", "roofline_fma_peak")),
      copy_(rt.kernel("roofline/roofline.cl", "roofline_copy_stream")),
      triad_(rt.kernel("roofline/roofline.cl", "roofline_triad_stream")),
      gather_(rt.kernel("roofline/roofline.cl", "roofline_gather_random")) {}

double RooflineProbe::run_fma(size_t work_items, int iters) {
  require(work_items > 0 && iters > 0, "roofline: fma probe needs work_items > 0 and iters > 0");
  if (work_items > fma_items_) {
    fma_out_ = cl::Buffer(rt_, work_items * sizeof(float));
    fma_items_ = work_items;
  }
  fma_.set_args(iters, kFmaA, kFmaB, fma_out_);
  return fma_.launch({work_items}).elapsed_ms();
}

std::vector<float> RooflineProbe::fma_output(size_t work_items) const {
  require(work_items <= fma_items_, "roofline: fma_output before run_fma");
  return fma_out_.read_vec<float>(work_items);
}

void RooflineProbe::alloc_stream(size_t n_floats) {
  require(n_floats > 0 && n_floats % 4 == 0, "roofline: stream size must be a multiple of 4");
  n_floats_ = n_floats;
  a_ = cl::Buffer(rt_, n_floats * sizeof(float));
  b_ = cl::Buffer::from(rt_, std::vector<float>(n_floats, 1.0f));
  c_ = cl::Buffer::from(rt_, std::vector<float>(n_floats, 2.0f));
  a_.fill_zero();
}

double RooflineProbe::run_copy() {
  require(n_floats_ > 0, "roofline: run_copy before alloc_stream");
  copy_.set_args(b_, a_);
  return copy_.launch({n_floats_ / 4}).elapsed_ms();
}

double RooflineProbe::run_triad(float s) {
  require(n_floats_ > 0, "roofline: run_triad before alloc_stream");
  triad_.set_args(s, a_, b_, c_);
  return triad_.launch({n_floats_ / 4}).elapsed_ms();
}

std::vector<float> RooflineProbe::stream_output() const { return a_.read_vec<float>(n_floats_); }

void RooflineProbe::alloc_gather_zero(size_t entries) {
  require(entries >= 2 && (entries & (entries - 1)) == 0 && entries <= (size_t(1) << 31),
          "roofline: gather table entries must be a power of two in [2, 2^31]");
  table_ = cl::Buffer(rt_, entries * 2 * sizeof(float));
  table_.fill_zero();
  table_entries_ = entries;
}

void RooflineProbe::alloc_gather(const std::vector<float>& table_float2) {
  const size_t entries = table_float2.size() / 2;
  require(table_float2.size() % 2 == 0 && entries >= 2 && (entries & (entries - 1)) == 0 &&
              entries <= (size_t(1) << 31),
          "roofline: gather table must hold a power of two of float2 entries in [2, 2^31]");
  table_ = cl::Buffer::from(rt_, table_float2);
  table_entries_ = entries;
}

double RooflineProbe::run_gather(size_t work_items) {
  require(table_entries_ > 0, "roofline: run_gather before alloc_gather");
  require(work_items > 0, "roofline: gather probe needs work_items > 0");
  if (work_items > gather_items_) {
    gather_out_ = cl::Buffer(rt_, work_items * sizeof(float));
    gather_items_ = work_items;
  }
  gather_.set_args(kGatherPerItem, uint32_t(table_entries_ - 1), table_, gather_out_);
  return gather_.launch({work_items}).elapsed_ms();
}

std::vector<float> RooflineProbe::gather_output(size_t work_items) const {
  require(work_items <= gather_items_, "roofline: gather_output before run_gather");
  return gather_out_.read_vec<float>(work_items);
}

void RooflineOptions::validate() const {
  check_range("roofline", "target_launch_ms", target_launch_ms, 1.0, 10000.0);
  check_range("roofline", "repetitions", repetitions, 1, 1000);
  require(stream_floats >= 1024 && stream_floats % 4 == 0,
          "roofline: stream_floats must be >= 1024 and a multiple of 4");
  require(gather_entries >= 1024 && (gather_entries & (gather_entries - 1)) == 0 &&
              gather_entries <= (size_t(1) << 31),
          "roofline: gather_entries must be a power of two in [1024, 2^31]");
  require(gather_items >= 1, "roofline: gather_items must be >= 1");
}

Json measure_roofline(cl::Runtime& rt, const RooflineOptions& opt) {
  opt.validate();
  RooflineProbe probe(rt);
  // Enough work-items to fill every compute unit many times over, then scale the loop
  // length so one launch takes about target_launch_ms.
  const size_t items = std::max<size_t>(4096, size_t(rt.device().compute_units) * 2048);
  int iters = 64;
  double ms = probe.run_fma(items, iters);  // also warms up the build
  for (int k = 0; k < 8 && ms < 0.5 * opt.target_launch_ms; ++k) {
    const double f = std::clamp(opt.target_launch_ms / std::max(ms, 1e-3), 2.0, 64.0);
    iters = int(std::min(1e7, iters * f));
    ms = probe.run_fma(items, iters);
  }
  std::vector<double> gflops, copy_gbs, triad_gbs;
  for (int r = 0; r < opt.repetitions; ++r)
    gflops.push_back(fma_flops(items, iters) / (probe.run_fma(items, iters) * 1e-3) * 1e-9);

  probe.alloc_stream(opt.stream_floats);
  probe.run_copy();
  probe.run_triad(3.0f);
  for (int r = 0; r < opt.repetitions; ++r) {
    copy_gbs.push_back(copy_bytes(opt.stream_floats) / (probe.run_copy() * 1e-3) * 1e-9);
    triad_gbs.push_back(triad_bytes(opt.stream_floats) / (probe.run_triad(3.0f) * 1e-3) * 1e-9);
  }
  std::vector<double> gathers;
  probe.alloc_gather_zero(opt.gather_entries);
  probe.run_gather(opt.gather_items);
  const double reads = double(opt.gather_items) * kGatherPerItem;
  for (int r = 0; r < opt.repetitions; ++r)
    gathers.push_back(reads / (probe.run_gather(opt.gather_items) * 1e-3));
  // The roofline is the best the device reaches: on a shared machine other processes only
  // ever slow a launch down, so the maximum is the estimate and the median shows the noise.
  return Json{{"peak_gflops_best", *std::max_element(gflops.begin(), gflops.end())},
              {"triad_gbs_best", *std::max_element(triad_gbs.begin(), triad_gbs.end())},
              {"copy_gbs_best", *std::max_element(copy_gbs.begin(), copy_gbs.end())},
              {"peak_gflops", summarize(gflops)},
              {"copy_gbs", summarize(copy_gbs)},
              {"triad_gbs", summarize(triad_gbs)},
              {"gathers_per_s_best", *std::max_element(gathers.begin(), gathers.end())},
              {"gathers_per_s", summarize(gathers)},
              {"gather_entries", opt.gather_entries},
              {"fma_work_items", items},
              {"fma_iters", iters},
              {"stream_floats", opt.stream_floats},
              {"method", "OpenCL event times; FLOP/s from float16 FMA chains, GB/s from float4 "
                         "copy (2 arrays) and triad (3 arrays), no write-allocate counted; "
                         "gathers/s from random float2 reads of a table of gather_entries"}};
}

}  // namespace sgnlf::harness
