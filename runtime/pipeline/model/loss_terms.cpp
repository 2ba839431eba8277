// The loss terms of loss_terms.hpp.
#include "pipeline/model/loss_terms.hpp"

#include "render/chamfer_loss.hpp"
#include "render/device_chamfer.hpp"

namespace sgnlf::pipeline {
namespace {

// The range loss (method.md §0): writes the output gradient and loss[0..2].
class RangeTerm final : public LossTerm {
 public:
  RangeTerm(render::RangeLoss& l, const cl::Buffer& buf) : loss_(l), buf_(buf) {}
  const char* name() const override { return "range"; }
  void add_output_gradient(LossPass& p) override {
    p.loss_buf.fill_zero();
    loss_.range(p.out, p.target, p.n_rays, p.grad_out, p.terms, p.loss_buf);
  }
  void read(render::LossValues& v) const override {
    const render::LossValues l = render::RangeLoss::read_losses(buf_);
    v.depth = l.depth, v.ret = l.ret, v.intensity = l.intensity;
  }
  void read_copy(render::LossValues& v, const std::vector<float>& loss) const override {
    v.depth = loss.at(0), v.ret = loss.at(1), v.intensity = loss.at(2);
  }
  double value() const override {
    render::LossValues v;
    read(v);
    return double(v.depth) + v.ret + v.intensity;
  }

 private:
  render::RangeLoss& loss_;
  const cl::Buffer& buf_;
};

// LiDAR-NeRF's range-image gradient loss on patch batches (method.md §1): adds to the depth
// column, loss[3].
class PatchGradientTerm final : public LossTerm {
 public:
  PatchGradientTerm(render::RangeLoss& l, const cl::Buffer& buf, int per_patch)
      : loss_(l), buf_(buf), per_patch_(per_patch) {}
  const char* name() const override { return "patch_gradient"; }
  void add_output_gradient(LossPass& p) override {
    if (!p.batch.patches) return;
    loss_.patch_gradient(p.out, p.target, p.n_rays / per_patch_, p.grad_out, p.terms,
                         p.loss_buf);
  }
  void read(render::LossValues& v) const override {
    v.grad = render::RangeLoss::read_losses(buf_).grad;
  }
  void read_copy(render::LossValues& v, const std::vector<float>& loss) const override {
    v.grad = loss.at(3);
  }
  double value() const override { return render::RangeLoss::read_losses(buf_).grad; }

 private:
  render::RangeLoss& loss_;
  const cl::Buffer& buf_;
  int per_patch_;
};

// LiDAR4D's Chamfer term on the batch's ray endpoints (method.md §2). Host: one read of the
// outputs and the gradient, geometry::KdTree's neighbours, one write. Device (the profile's
// chamfer: device): render::DeviceChamfer on the model's output, target and direction buffers,
// the gradient added there and the value left in a device float, read only by value().
class ChamferTerm final : public LossTerm {
 public:
  ChamferTerm(float scale, float weight, cl::Runtime* device) : scale_(scale), weight_(weight) {
    if (!device) return;
    device_ = std::make_unique<render::DeviceChamfer>(*device);
    value_ = cl::Buffer(*device, sizeof(float));
  }
  const char* name() const override { return "chamfer"; }
  void add_output_gradient(LossPass& p) override {
    if (device_) {
      require(p.directions != nullptr, "ChamferTerm: the pass has no device directions");
      device_->ray(*p.directions, p.out, p.target, p.n_rays, scale_, weight_, p.grad_out, value_,
                   0);
      on_device_ = true;
      return;
    }
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
  void read(render::LossValues&) const override {}
  // Device: one blocking read of the value (a logged step's).
  double value() const override {
    return on_device_ ? double(value_.read_vec<float>(1)[0]) : last_;
  }

 private:
  float scale_, weight_;
  double last_ = 0.0;
  std::unique_ptr<render::DeviceChamfer> device_;
  cl::Buffer value_;
  bool on_device_ = false;
};

// NeuRAD's weight carving (render::WeightCarving): adds to the σ-logit gradient. Its value: the
// per-ray terms summed on the host in double, or (device_sums) on the device in the loss
// kernels' fixed tree into loss_buf[kCarveSlot].
class CarveTerm final : public LossTerm {
 public:
  CarveTerm(render::WeightCarving& c, const render::RenderConfig& rc, float scale,
            render::RangeLoss& range, const cl::Buffer& loss_buf, bool device_sums)
      : carve_(c), rc_(rc), scale_(scale), range_(range), buf_(loss_buf),
        device_sums_(device_sums) {}
  const char* name() const override { return "carve"; }
  void add_sample_gradient(LossPass& p) override {
    const float half_w = float(rc_.surface_band_m(p.step)) * scale_;
    carve_.add(p.t, p.h0, p.weights, p.target, p.n_rays, p.per_ray, half_w, p.g_h0);
    if (device_sums_)
      range_.reduce(carve_.terms(), p.n_rays, 1, 0, 1.0f, p.loss_buf, int(kCarveSlot));
  }
  void read(render::LossValues& v) const override { v.carve = float(value()); }
  void read_copy(render::LossValues& v, const std::vector<float>& loss) const override {
    v.carve = device_sums_ ? loss.at(kCarveSlot) : float(carve_.read());
  }
  double value() const override {
    if (!device_sums_) return carve_.read();
    if (carve_.n_rays() == 0) return 0.0;
    float s = 0.0f;
    buf_.read(&s, sizeof s, kCarveSlot * sizeof(float));
    return double(s);
  }

 private:
  render::WeightCarving& carve_;
  render::RenderConfig rc_;
  float scale_;
  render::RangeLoss& range_;
  const cl::Buffer& buf_;
  bool device_sums_;
};

}  // namespace

std::vector<std::unique_ptr<LossTerm>> make_loss_terms(const TrainConfig& c, float scene_scale,
                                                        render::RangeLoss& range,
                                                        const cl::Buffer& loss_buf,
                                                        render::WeightCarving* carve,
                                                        bool device_sums,
                                                        cl::Runtime* device_chamfer) {
  std::vector<std::unique_ptr<LossTerm>> terms;
  terms.push_back(std::make_unique<RangeTerm>(range, loss_buf));
  terms.push_back(std::make_unique<PatchGradientTerm>(
      range, loss_buf, c.render.patch_rows * c.render.patch_cols));
  if (c.lidar4d && c.lidar4d->chamfer_weight > 0.0)
    terms.push_back(std::make_unique<ChamferTerm>(scene_scale, float(c.lidar4d->chamfer_weight),
                                                  device_chamfer));
  if (carve)
    terms.push_back(std::make_unique<CarveTerm>(*carve, c.render, scene_scale, range, loss_buf,
                                                device_sums));
  return terms;
}

}  // namespace sgnlf::pipeline
