// LiDAR4D's Chamfer term and flow supervision under the device profile's chamfer: device
// (render::DeviceChamfer, DeviceSceneFlowLoss through the Chamfer and flow loss terms)
// against chamfer: host, the k-d tree path: the output gradient and the Chamfer value of one
// pass, the flow supervision's value and parameter gradient, a whole gpu-profile step's loss
// and gradient; two gpu-profile steps from one seed give the same bits.
#include <catch2/catch.hpp>

#include <memory>

#include "pipeline/model/ray_batch.hpp"
#include "pipeline/train/flow_supervision.hpp"
#include "support/device_tolerance.hpp"
#include "support/test_device.hpp"
#include "tiny_scene.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;
using namespace sgnlf::pipeline;

namespace {

cl::DeviceProfile with_chamfer(cl::DeviceProfile p, cl::ChamferSearch c) {
  p.chamfer = c;
  return p;
}

// A model made under `profile` (the runtime's profile is put back after).
std::unique_ptr<LidarNerfModel> model_under(const cl::DeviceProfile& profile, const Scene& scene,
                                            const TrainConfig& c, uint64_t seed) {
  cl::Runtime& rt = test::runtime();
  const cl::DeviceProfile saved = rt.device_profile();
  rt.set_device_profile(profile);
  try {
    auto m = std::make_unique<LidarNerfModel>(rt, c, float(scene.norm.scale), model_capacity(c));
    m->init_params(seed);
    rt.set_device_profile(saved);
    return m;
  } catch (...) {
    rt.set_device_profile(saved);
    throw;
  }
}

// Runs f with the runtime under `profile` (kernels pick their shapes at launch).
template <class F>
void under(const cl::DeviceProfile& profile, F&& f) {
  cl::Runtime& rt = test::runtime();
  const cl::DeviceProfile saved = rt.device_profile();
  rt.set_device_profile(profile);
  try {
    f();
  } catch (...) {
    rt.set_device_profile(saved);
    throw;
  }
  rt.set_device_profile(saved);
}

// The flow supervision's term alone, in a pass of its own at the batch frame of (seed, step):
// its value and its parameter gradient.
struct FlowResult {
  double loss = 0;
  std::vector<float> grad;
};
FlowResult flow_step(const cl::DeviceProfile& p, const Scene& scene, const TrainConfig& c,
                     uint64_t seed, long step) {
  FlowResult r;
  under(p, [&] {
    auto m = model_under(p, scene, c, 5);
    const auto flow = make_flow_supervision(p.chamfer, test::tiny_dataset(), scene, c, 3);
    RayBatch b;
    b.frame = batch_frame(scene, seed, step);
    m->set_frame(b.frame, int(scene.T_world_lidar.size()));
    FieldPass field(*m, b, seed, step);
    flow->add_field_gradient(field);
    REQUIRE(field.wrote_gradient());
    r.grad = m->read_term_gradient();
    r.loss = flow->last_value();
  });
  return r;
}

}  // namespace

TEST_CASE("lidar4d: the Chamfer term on the device equals the host's k-d tree path",
          "[pipeline][lidar4d][chamfer_device]") {
  const Scene scene = make_scene(test::tiny_dataset());
  const TrainConfig c = test::tiny_lidar4d();
  // The cpu profile with either Chamfer: every other kernel the same bits, so the output
  // gradients differ by the Chamfer term's rounding only.
  const cl::DeviceProfile host = with_chamfer(cl::cpu_profile(), cl::ChamferSearch::Host),
                          device = with_chamfer(cl::cpu_profile(), cl::ChamferSearch::Device);
  const RayBatch b = draw_ray_batch(scene, c, 5, 14);
  std::vector<float> g[2];
  double value[2] = {0, 0};
  int k = 0;
  for (const auto& p : {host, device}) {
    under(p, [&] {
      auto m = model_under(p, scene, c, 7);
      m->set_frame(b.frame, int(scene.T_world_lidar.size()));
      m->forward_backward(b, 9, 14);
      g[k] = m->read_output_gradient();
      value[k] = m->read_losses().value("chamfer");
    });
    ++k;
  }
  REQUIRE(value[0] > 0.0);
  CHECK(test::sym_rel_err({float(value[1])}, {float(value[0])}, 1e-12) <= 1e-5);
  // The range loss's share is the same bits; the Chamfer share rounds within float accuracy
  // of the larger of the two.
  CHECK(test::sym_rel_err(g[1], g[0], 1e-6) <= 1e-4);
}

TEST_CASE("lidar4d: the flow supervision on the device equals the host's",
          "[pipeline][lidar4d][chamfer_device]") {
  const Scene scene = make_scene(test::tiny_dataset());
  const TrainConfig c = test::tiny_lidar4d();
  const cl::DeviceProfile host = with_chamfer(cl::cpu_profile(), cl::ChamferSearch::Host),
                          device = with_chamfer(cl::cpu_profile(), cl::ChamferSearch::Device);
  for (const long step : {0L, 3L}) {
    CAPTURE(step);
    const FlowResult h = flow_step(host, scene, c, 11, step), d = flow_step(device, scene, c, 11, step);
    REQUIRE(h.loss > 0.0);
    CHECK(test::sym_rel_err({float(d.loss)}, {float(h.loss)}, 1e-12) <= 1e-5);
    // The same flow (cpu kernels), dL/dflow within float rounding, then the same backward:
    // the gradient as a whole within that rounding.
    CHECK(test::nmse(d.grad, h.grad) <= 1e-10);
  }
}

TEST_CASE("lidar4d: a gpu-profile step with the device Chamfer equals the host path; repeats bit for bit",
          "[pipeline][lidar4d][chamfer_device][gpu_profile]") {
  const Scene scene = make_scene(test::tiny_dataset());
  const TrainConfig c = test::tiny_lidar4d();
  const cl::DeviceProfile gpu = cl::gpu_profile();
  REQUIRE(gpu.chamfer == cl::ChamferSearch::Device);
  const cl::DeviceProfile gpu_host = with_chamfer(gpu, cl::ChamferSearch::Host);
  struct Step {
    std::vector<float> grad, params;
    double loss = 0, flow = 0, chamfer = 0;
  };
  auto run = [&](const cl::DeviceProfile& p, long steps) {
    Step s;
    under(p, [&] {
      auto m = model_under(p, scene, c, 2);
      GroundTruthPoseStep gt(scene, c);
      auto& flow = static_cast<FlowSupervision&>(
          m->add_loss(make_flow_supervision(p.chamfer, test::tiny_dataset(), scene, c, 3)));
      FieldOptimizer optim(*m, c);
      for (long step = 0; step < steps; ++step) gt.step(*m, optim, 4, step, 1e-3f);
      s.grad = m->read_gradient();
      s.params = m->params();
      const LossReport l = m->read_losses();
      s.loss = l.total();
      s.flow = flow.last_value();
      s.chamfer = l.value("chamfer");
      CHECK(l.value("flow") == s.flow);
    });
    return s;
  };
  // Deterministic: the same bits from the same seed over two steps.
  const Step a = run(gpu, 2), b = run(gpu, 2);
  CHECK(test::same_bits(a.grad, b.grad));
  CHECK(test::same_bits(a.params, b.params));
  CHECK(a.loss == b.loss);
  CHECK(a.flow == b.flow);
  CHECK(a.chamfer == b.chamfer);
  // Against the host Chamfer under the same profile, one step (a second would start from
  // parameters that differ by the first one's rounding, which Adam's first step turns into ±lr
  // for a tiny gradient of either sign): loss, flow loss, Chamfer value and the gradient.
  const Step d = run(gpu, 1), h = run(gpu_host, 1);
  REQUIRE(h.flow > 0.0);
  REQUIRE(h.chamfer > 0.0);
  CHECK(test::sym_rel_err({float(d.loss)}, {float(h.loss)}, 1e-12) <= 1e-5);
  CHECK(test::sym_rel_err({float(d.flow)}, {float(h.flow)}, 1e-12) <= 1e-5);
  CHECK(test::sym_rel_err({float(d.chamfer)}, {float(h.chamfer)}, 1e-12) <= 1e-5);
  CHECK(test::nmse(d.grad, h.grad) <= 1e-10);
}
