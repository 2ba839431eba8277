// The model's list of loss terms (loss_term.hpp) and the config's built-in ones: the range loss,
// LiDAR-NeRF's patch gradient loss, LiDAR4D's Chamfer term and NeuRAD's weight carving. The
// list is made from the config once (make_loss_terms); a step part adds its own terms
// (LidarNerfModel::add_loss). Its first entry is the range term, the one term that writes the
// per-ray output gradient: a RangeTerm by type, held apart from the terms that add to it.
// Where a device profile entry chooses an algorithm (chamfer: host or device; loss_reduce:
// carving's terms summed on the host or the device), make_loss_terms picks the term's class
// once.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "cl/runtime.hpp"
#include "pipeline/config/train_config.hpp"
#include "pipeline/model/loss_term.hpp"
#include "render/range_loss.hpp"
#include "render/weight_carving.hpp"

namespace sgnlf::pipeline {

// The model's loss buffer: render::RangeLoss's kLossFloats (depth, ret, intensity, grad), then
// weight carving's sum when the device profile's loss_reduce is device (slot kCarveSlot).
inline constexpr size_t kCarveSlot = render::kLossFloats;
inline constexpr size_t kLossBufferFloats = render::kLossFloats + 1;

// The range loss (method.md §0): writes the per-ray output gradient and the loss buffer's first
// three values (the buffer zeroed first); reports "depth", "return", "intensity".
class RangeTerm final : public LossTerm {
 public:
  explicit RangeTerm(render::RangeLoss& l) : loss_(l) {}
  const char* name() const override { return "range"; }
  void write_output_gradient(LossPass& p);
  void report(LossReport& r, const std::vector<float>& loss) const override;

 private:
  render::RangeLoss& loss_;
};

class LossList {
 public:
  LossList() = default;
  explicit LossList(std::unique_ptr<RangeTerm> range) : range_(std::move(range)) {}
  RangeTerm& range() { return *range_; }
  // The terms after the range term, in the order they were added.
  const std::vector<std::unique_ptr<LossTerm>>& others() const { return others_; }
  LossTerm& add(std::unique_ptr<LossTerm> t) {
    others_.push_back(std::move(t));
    return *others_.back();
  }
  // Every term, the range term first.
  template <class F>
  void each(F&& f) const {
    f(static_cast<LossTerm&>(*range_));
    for (const auto& t : others_) f(*t);
  }
  std::vector<std::string> names() const;

 private:
  std::unique_ptr<RangeTerm> range_;
  std::vector<std::unique_ptr<LossTerm>> others_;
};

// The config's terms, in order: "range", "patch_gradient" (reports "grad"; on patch batches),
// "chamfer" (lidar4d.chamfer_weight > 0), "carve" (render.weights.carve > 0). `range` and
// `carve` (null when the config has no carving) must outlive the list. The device profile of
// `rt` chooses the Chamfer term's class (chamfer: host = the batch's depths on the host and
// geometry::KdTree, 3 blocking transfers a pass; device = render::DeviceChamfer, its value read
// only when reported) and carving's (loss_reduce: host = its per-ray terms summed in double when
// reported; device = summed by render_loss_reduce into the loss buffer's kCarveSlot).
LossList make_loss_terms(cl::Runtime& rt, const TrainConfig& c, float scene_scale,
                         render::RangeLoss& range, render::WeightCarving* carve);

}  // namespace sgnlf::pipeline
