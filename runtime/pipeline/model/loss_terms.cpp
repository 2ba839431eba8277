// The built-in loss terms of loss_terms.hpp.
#include "pipeline/model/loss_terms.hpp"

#include "render/chamfer_loss.hpp"
#include "render/device_chamfer.hpp"

namespace sgnlf::pipeline {

void RangeTerm::write_output_gradient(LossPass& p) {
  p.loss_buf.fill_zero();
  loss_.range(p.out, p.target, p.n_rays, p.grad_out, p.terms, p.loss_buf);
}

void RangeTerm::report(LossReport& r, const std::vector<float>& loss) const {
  r.add("depth", loss.at(0));
  r.add("return", loss.at(1));
  r.add("intensity", loss.at(2));
}

std::vector<std::string> LossList::names() const {
  std::vector<std::string> n;
  each([&](const LossTerm& t) { n.emplace_back(t.name()); });
  return n;
}

namespace {

// LiDAR-NeRF's range-image gradient loss on patch batches (method.md §1): adds to the depth
// column, loss[3]; reports "grad".
class PatchGradientTerm final : public LossTerm {
 public:
  PatchGradientTerm(render::RangeLoss& l, int per_patch) : loss_(l), per_patch_(per_patch) {}
  const char* name() const override { return "patch_gradient"; }
  void add_output_gradient(LossPass& p) override {
    if (!p.batch.patches) return;
    loss_.patch_gradient(p.out, p.target, p.n_rays / per_patch_, p.grad_out, p.terms,
                         p.loss_buf);
  }
  void report(LossReport& r, const std::vector<float>& loss) const override {
    r.add("grad", loss.at(3));
  }

 private:
  render::RangeLoss& loss_;
  int per_patch_;
};

// LiDAR4D's Chamfer term on the batch's ray endpoints (method.md §2), the profile's chamfer:
// host. One read of the outputs and the gradient, geometry::KdTree's neighbours, one write.
class HostChamferTerm final : public LossTerm {
 public:
  HostChamferTerm(float scale, float weight) : scale_(scale), weight_(weight) {}
  const char* name() const override { return "chamfer"; }
  void add_output_gradient(LossPass& p) override {
    const RayBatch& b = p.batch;
    const int R = b.n_rays;
    const std::vector<float> out = p.out.read_vec<float>(size_t(R) * 3);
    std::vector<float> grad = p.grad_out.read_vec<float>(size_t(R) * 3);
    // Rays without a return carry depth 0 in both sets, as LiDAR4D masks them.
    std::vector<float> depth(static_cast<size_t>(R)), gt(static_cast<size_t>(R));
    for (size_t i = 0; i < size_t(R); ++i) {
      const float mask = b.label[i] > 0.5f ? 1.0f : 0.0f;
      depth[i] = out[3 * i] * mask;
      gt[i] = b.range[i] * mask;
    }
    const render::RayChamferLoss c =
        render::ray_chamfer_loss(b.directions, depth, gt, scale_, weight_);
    for (size_t i = 0; i < size_t(R); ++i)
      if (b.label[i] > 0.5f) grad[3 * i] += c.d_depth[i];
    p.grad_out.write_vec(grad);
    last_ = c.loss;
  }
  void report(LossReport& r, const std::vector<float>&) const override { r.add("chamfer", last_); }

 private:
  float scale_, weight_;
  double last_ = 0.0;
};

// The same, the profile's chamfer: device: render::DeviceChamfer on the model's output, target
// and direction buffers, the gradient added there and the value left in a device float, read
// only when reported.
class DeviceChamferTerm final : public LossTerm {
 public:
  DeviceChamferTerm(cl::Runtime& rt, float scale, float weight)
      : scale_(scale), weight_(weight), device_(rt), value_(rt, sizeof(float)) {}
  const char* name() const override { return "chamfer"; }
  void add_output_gradient(LossPass& p) override {
    device_.ray(p.directions, p.out, p.target, p.n_rays, scale_, weight_, p.grad_out, value_, 0);
    ran_ = true;
  }
  void report(LossReport& r, const std::vector<float>&) const override {
    r.add("chamfer", ran_ ? double(value_.read_vec<float>(1)[0]) : 0.0);
  }

 private:
  float scale_, weight_;
  render::DeviceChamfer device_;
  cl::Buffer value_;
  bool ran_ = false;
};

// NeuRAD's weight carving (render::WeightCarving): adds to the σ-logit gradient; reports
// "carve". The profile's loss_reduce: host: its per-ray terms summed on the host in double when
// reported (rounded to float, as the loss buffer's values).
class HostSumCarveTerm : public LossTerm {
 public:
  HostSumCarveTerm(render::WeightCarving& c, const render::RenderConfig& rc, float scale)
      : carve_(c), rc_(rc), scale_(scale) {}
  const char* name() const override { return "carve"; }
  void add_sample_gradient(LossPass& p) override {
    const float half_w = float(rc_.surface_band_m(p.step)) * scale_;
    carve_.add(p.t, p.h0, p.weights, p.target, p.n_rays, p.per_ray, half_w, p.g_h0);
  }
  void report(LossReport& r, const std::vector<float>&) const override {
    r.add("carve", float(carve_.read()));
  }

 protected:
  render::WeightCarving& carve_;

 private:
  render::RenderConfig rc_;
  float scale_;
};

// loss_reduce: device: the per-ray terms summed on the device in the loss kernels' fixed tree
// into loss[kCarveSlot], read with the rest of the buffer.
class DeviceSumCarveTerm final : public HostSumCarveTerm {
 public:
  DeviceSumCarveTerm(render::WeightCarving& c, const render::RenderConfig& rc, float scale,
                     render::RangeLoss& range)
      : HostSumCarveTerm(c, rc, scale), range_(range) {}
  void add_sample_gradient(LossPass& p) override {
    HostSumCarveTerm::add_sample_gradient(p);
    range_.reduce(carve_.terms(), p.n_rays, 1, 0, 1.0f, p.loss_buf, int(kCarveSlot));
  }
  void report(LossReport& r, const std::vector<float>& loss) const override {
    r.add("carve", loss.at(kCarveSlot));
  }

 private:
  render::RangeLoss& range_;
};

}  // namespace

LossList make_loss_terms(cl::Runtime& rt, const TrainConfig& c, float scene_scale,
                         render::RangeLoss& range, render::WeightCarving* carve) {
  const cl::DeviceProfile& profile = rt.device_profile();
  LossList terms(std::make_unique<RangeTerm>(range));
  terms.add(std::make_unique<PatchGradientTerm>(range, c.render.patch_rows * c.render.patch_cols));
  if (c.lidar4d && c.lidar4d->chamfer_weight > 0.0) {
    const float w = float(c.lidar4d->chamfer_weight);
    if (profile.chamfer == cl::ChamferSearch::Device)
      terms.add(std::make_unique<DeviceChamferTerm>(rt, scene_scale, w));
    else
      terms.add(std::make_unique<HostChamferTerm>(scene_scale, w));
  }
  if (carve) {
    if (profile.loss_reduce == cl::LossReduce::Device)
      terms.add(std::make_unique<DeviceSumCarveTerm>(*carve, c.render, scene_scale, range));
    else
      terms.add(std::make_unique<HostSumCarveTerm>(*carve, c.render, scene_scale));
  }
  return terms;
}

}  // namespace sgnlf::pipeline
