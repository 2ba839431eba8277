// Mlp host code: spec checks, the parameter layout and init, and the forward and backward
// passes layer by layer; the kernels of each layer and their launches (both GEMM variants of
// the device profile) are in mlp_gemm.cpp.
#include "field/mlp.hpp"

#include <algorithm>
#include <cmath>

#include "cl/launch.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"

namespace sgnlf::field {
namespace {
void check_bytes(const cl::Buffer& b, size_t floats, const char* what) {
  if (b.bytes() < floats * sizeof(float))
    throw Error(std::string("Mlp: buffer '") + what + "' has " + std::to_string(b.bytes()) +
                " bytes, needs " + std::to_string(floats * sizeof(float)));
}
}  // namespace

void MlpSpec::validate() const {
  check_range("mlp", "n_in", n_in, 1, 128);
  check_range("mlp", "n_in_group", n_in_group, 0, 128);
  check_range("mlp", "in_offset", in_offset, 0, 1 << 20);
  if (in_stride != 0 && in_stride < in_offset + n_in)
    throw ConfigError("mlp: 'in_stride' " + std::to_string(in_stride) + " is below in_offset + n_in = " +
                      std::to_string(in_offset + n_in));
  if (in_stride == 0 && in_offset != 0)
    throw ConfigError("mlp: 'in_offset' needs an explicit 'in_stride'");
  if (layers.empty()) throw ConfigError("mlp: at least one layer is required");
  check_range("mlp", "towers", towers, 1, 8);
  for (size_t l = 0; l < layers.size(); ++l) {
    const std::string key = "layers[" + std::to_string(l) + "].width";
    check_range("mlp", key, layers[l].width, 1, 128);
    if (layers[l].width % towers != 0)
      throw ConfigError("mlp: '" + key + "' = " + std::to_string(layers[l].width) +
                        " is not divisible by towers = " + std::to_string(towers));
  }
}

double MlpSpec::macs_per_point() const {
  double macs = 0;
  int in = n_in;
  for (size_t l = 0; l < layers.size(); ++l) {
    // After layer 0 a tower's units see only their tower's inputs.
    macs += double(in) * layers[l].width / (l == 0 ? 1 : towers);
    in = layers[l].width;
  }
  return macs;
}

MlpSpec make_mlp_spec(int n_in, int width, int hidden, int n_out, Activation act,
                      Activation out_act) {
  MlpSpec s;
  s.n_in = n_in;
  for (int h = 0; h < hidden; ++h) s.layers.push_back({width, act});
  s.layers.push_back({n_out, out_act});
  return s;
}

Mlp::Mlp(cl::Runtime& rt, const MlpSpec& spec)
    : rt_(rt), profile_(rt.device_profile()), spec_(spec) {
  spec_.validate();
  const int n_layers = int(spec_.layers.size());
  const int n_group = spec_.n_in_group;
  // The program of the last layer built (file, options): the tower mask's kernel reuses it.
  std::pair<std::string, std::string> last;
  int n_in = spec_.n_in;
  for (int l = 0; l < n_layers; ++l) {
    const auto& ls = spec_.layers[size_t(l)];
    Layer L{};
    L.n_in = n_in;
    L.n_rows = l == 0 ? n_in + n_group : n_in;
    L.in_stride = l == 0 ? spec_.row_stride() : pad16(n_in);
    L.out = ls.width;
    L.out_pad = pad16(ls.width);
    L.out_stride = l == n_layers - 1 ? ls.width : L.out_pad;
    L.act = ls.activation;
    L.store_pre = L.act == Activation::Sine ||
                  (l == n_layers - 1 && L.act != Activation::None);
    layer_off_.push_back(n_params_);
    n_params_ += size_t(L.n_rows + 1) * size_t(L.out_pad);
    const bool prev_pre = l > 0 && layers_.back().store_pre;
    const int prev_act = l > 0 ? int(layers_.back().act) : -1;
    last = build_layer(L, l == 0 ? spec_.in_offset : 0, prev_act, prev_pre,
                       l == 0 && n_group > 0, l > 0 && spec_.towers > 1);
    if (l == 0 && n_group > 0) {
      // The grouped part: a linear layer of n_group inputs whose weights are rows n_in .. of
      // layer 0 and whose bias is layer 0's bias (both follow at n_in · out_pad).
      group_.n_in = group_.n_rows = group_.in_stride = n_group;
      group_.out = L.out;
      group_.out_pad = group_.out_stride = L.out_pad;
      group_.act = Activation::None;
      group_.store_pre = false;
      last = build_layer(group_, 0, -1, false, false, false);
    }
    layers_.push_back(std::move(L));
    n_in = ls.width;
  }
  if (spec_.towers > 1 && n_layers > 1) {
    // The mask of the off-tower weights; its kernel reuses the last layer's program.
    std::vector<uint8_t> keep;
    keep.reserve(n_params_ - layer_off_[1]);
    for (size_t l = 1; l < layers_.size(); ++l)
      for (int i = 0; i <= layers_[l].n_rows; ++i)
        for (int o = 0; o < layers_[l].out_pad; ++o) keep.push_back(off_tower(l, i, o) ? 0 : 1);
    tower_count_ = keep.size();
    tower_keep_ = cl::Buffer::from(rt_, keep);
    tower_mask_ = rt_.kernel(last.first, "field_mlp_tower_mask", last.second);
  }
}

bool Mlp::off_tower(size_t l, int i, int o) const {
  const Layer& L = layers_[l];
  const int T = spec_.towers;
  if (T <= 1 || l == 0 || i >= L.n_rows || o >= L.out) return false;
  return i / (L.n_in / T) != o / (L.out / T);
}

void Mlp::init_params(std::vector<float>& host_params, size_t offset, uint64_t seed) const {
  if (offset + n_params_ > host_params.size())
    throw Error("Mlp::init_params: slice exceeds buffer of " +
                std::to_string(host_params.size()) + " floats");
  Rng rng(seed, 0x4d4cu);
  for (size_t l = 0; l < layers_.size(); ++l) {
    const Layer& L = layers_[l];
    const double gain = L.act == Activation::Relu ? 6.0 : 3.0;
    // Fan-in includes grouped inputs; after layer 0 a tower's units see n_in / T inputs.
    const int fan_in = l == 0 ? L.n_rows : L.n_rows / spec_.towers;
    const float bound = float(std::sqrt(gain / fan_in));
    float* w = host_params.data() + offset + layer_off_[l];
    for (int i = 0; i <= L.n_rows; ++i)
      for (int o = 0; o < L.out_pad; ++o) {
        const float u = rng.uniform(-bound, bound);  // drawn for every slot: layout-stable
        w[size_t(i) * L.out_pad + o] =
            (i < L.n_rows && o < L.out && !off_tower(l, i, o)) ? u : 0.0f;
      }
  }
}

void Mlp::ensure(MlpContext& ctx, int n) const {
  if (ctx.capacity >= size_t(n) && ctx.post.size() == layers_.size()) return;
  ctx.post.clear();
  ctx.pre.clear();
  for (const Layer& L : layers_) {
    ctx.post.emplace_back(rt_, size_t(n) * L.out_pad * sizeof(float));
    ctx.pre.push_back(L.store_pre ? cl::Buffer(rt_, size_t(n) * L.out_pad * sizeof(float))
                                  : cl::Buffer());
  }
  ctx.capacity = size_t(n);
}

void Mlp::forward(const cl::Buffer& params, size_t offset, const cl::Buffer& in, int n,
                  cl::Buffer& out, MlpContext& ctx, const cl::Buffer* group_in, int group,
                  const GroupIndex* index) {
  check_bytes(params, offset + n_params_, "params");
  check_bytes(in, size_t(std::max(n, 0)) * spec_.row_stride(), "in");
  check_bytes(out, size_t(std::max(n, 0)) * spec_.n_out(), "out");
  const bool grouped = spec_.n_in_group > 0;
  const bool indexed = grouped && index != nullptr;
  if (index && !grouped) throw Error("Mlp::forward: a group index given, the MLP has no grouped inputs");
  if (indexed) {
    if (!group_in || !index->point_group || !index->offsets || index->n_groups < 1)
      throw Error("Mlp::forward: a group index needs group_in, point_group, offsets and n_groups >= 1");
    check_bytes(*index->point_group, size_t(std::max(n, 0)), "point_group");
    check_bytes(*index->offsets, size_t(index->n_groups) + 1, "offsets");
    check_bytes(*group_in, size_t(index->n_groups) * spec_.n_in_group, "group_in");
  } else if (grouped) {
    if (!group_in || group < 1 || n % group != 0)
      throw Error("Mlp::forward: grouped inputs need group_in and a group size dividing n = " +
                  std::to_string(n) + " (group " + std::to_string(group) + ")");
    check_bytes(*group_in, size_t(n / group) * spec_.n_in_group, "group_in");
  }
  ctx.n = n;
  ctx.in = &in;
  ctx.group_in = grouped ? group_in : nullptr;
  ctx.group = grouped ? (indexed ? 1 : group) : 0;
  ctx.index = indexed ? *index : GroupIndex{};
  if (n <= 0) return;
  ensure(ctx, n);
  if (grouped) {
    const int ng = indexed ? index->n_groups : n / group;
    const size_t need = size_t(ng) * group_.out_pad * sizeof(float);
    if (ctx.group_pre.bytes() < need) ctx.group_pre = cl::Buffer(rt_, need);
    launch_fwd(group_, ng, params, uint32_t(offset + layer_off_[0] + size_t(spec_.n_in) * group_.out_pad),
               *group_in, ctx.group_pre, ctx.group_pre, ctx.group_pre, 1, ctx.group_pre, 0);
  }
  for (size_t l = 0; l < layers_.size(); ++l) {
    Layer& L = layers_[l];
    const cl::Buffer& src = l == 0 ? in : ctx.post[l - 1];
    cl::Buffer& dst = l + 1 == layers_.size() ? out : ctx.post[l];
    cl::Buffer& pre = L.store_pre ? ctx.pre[l] : dst;
    const cl::Buffer& gbias = l == 0 && grouped ? ctx.group_pre : dst;  // unused without groups
    const cl::Buffer& gidx = indexed && l == 0 ? *index->point_group : dst;  // unused otherwise
    launch_fwd(L, n, params, uint32_t(offset + layer_off_[l]), src, dst, pre, gbias,
               std::max(ctx.group, 1), gidx, int(indexed && l == 0));
  }
}

void Mlp::ensure_scratch(int n) {
  int max_pad = 16;
  size_t partial = 0;
  const size_t ch = chunks(size_t(n));
  for (const Layer& L : layers_) {
    max_pad = std::max({max_pad, L.out_pad, pad16(L.n_in)});
    partial = std::max(partial, ch * size_t(L.n_in + 1) * L.out_pad);
  }
  if (spec_.n_in_group > 0)  // the grouped pass has at most as many chunks as the per-point one
    partial = std::max(partial, ch * size_t(group_.n_in + 1) * group_.out_pad);
  if (scratch_points_ < size_t(n)) {
    for (auto& b : d_pre_) b = cl::Buffer(rt_, size_t(n) * max_pad * sizeof(float));
    scratch_points_ = size_t(n);
  }
  if (partial_floats_ < partial) {
    partial_ = cl::Buffer(rt_, partial * sizeof(float));
    partial_floats_ = partial;
  }
  if (!wt_ && !local_tiles()) wt_ = cl::Buffer(rt_, size_t(128) * 128 * sizeof(float));
}

void Mlp::backward(const cl::Buffer& params, size_t offset, const MlpContext& ctx,
                   const cl::Buffer& out, const cl::Buffer& d_out, cl::Buffer& grad,
                   size_t grad_offset, cl::Buffer* d_in, cl::Buffer* d_group_in) {
  const int n = ctx.n;
  check_bytes(grad, grad_offset + n_params_, "grad");
  if (n <= 0 || !ctx.in) throw Error("Mlp::backward: context holds no forward pass");
  const bool grouped = spec_.n_in_group > 0;
  if (grouped && (!ctx.group_in || ctx.group < 1))
    throw Error("Mlp::backward: grouped MLP without the forward's group input");
  if (d_group_in && !grouped) throw Error("Mlp::backward: d_group_in given, the MLP has no grouped inputs");
  check_bytes(d_out, size_t(n) * spec_.n_out(), "d_out");
  if (d_in) check_bytes(*d_in, size_t(n) * spec_.row_stride(), "d_in");
  const bool indexed = grouped && ctx.index.offsets != nullptr;
  const int ng = grouped ? (indexed ? ctx.index.n_groups : n / ctx.group) : 0;
  if (d_group_in) check_bytes(*d_group_in, size_t(ng) * spec_.n_in_group, "d_group_in");
  ensure_scratch(n);
  const int last = int(layers_.size()) - 1;
  int cur = 0;
  {
    Layer& L = layers_[size_t(last)];
    const cl::Buffer& y = L.store_pre ? ctx.pre[size_t(last)] : out;
    launch_bwd_out(L, n, d_out, y, d_pre_[cur]);
  }
  for (int l = last; l >= 0; --l) {
    Layer& L = layers_[size_t(l)];
    const cl::Buffer& src = l == 0 ? *ctx.in : ctx.post[size_t(l - 1)];
    // Layer 0 with groups: this pass writes the x rows and a provisional bias row, which the
    // grouped pass below overwrites with the y rows and the true bias (in-order queue).
    weight_grad(L, src, d_pre_[cur], n, grad, grad_offset + layer_off_[size_t(l)]);
    if (l == 0 && grouped) {
      const size_t need = size_t(ng) * group_.out_pad * sizeof(float);
      if (d_group_.bytes() < need) d_group_ = cl::Buffer(rt_, need);
      launch_group_sum(L, ng, ctx.group, d_pre_[cur], d_group_,
                       indexed ? *ctx.index.offsets : d_group_, int(indexed));
      const size_t y_rows = size_t(spec_.n_in) * group_.out_pad;
      weight_grad(group_, *ctx.group_in, d_group_, ng, grad, grad_offset + layer_off_[0] + y_rows);
      if (d_group_in)
        launch_bwd_in(group_, ng, params, uint32_t(offset + layer_off_[0] + y_rows), d_group_,
                      d_group_, *d_group_in);
    }
    if (l == 0 && !d_in) break;
    cl::Buffer& dst = l == 0 ? *d_in : d_pre_[1 - cur];
    const cl::Buffer& prev =
        l == 0 ? d_out
               : (layers_[size_t(l - 1)].store_pre ? ctx.pre[size_t(l - 1)] : ctx.post[size_t(l - 1)]);
    launch_bwd_in(L, n, params, uint32_t(offset + layer_off_[size_t(l)]), d_pre_[cur], prev, dst);
    cur = 1 - cur;
  }
  if (tower_count_ > 0) {  // off-tower weights: exactly zero gradient
    tower_mask_.set_args(int(tower_count_), tower_keep_, grad,
                         uint32_t(grad_offset + layer_off_[1]));
    cl::launch_1d(tower_mask_, tower_count_);
  }
}

}  // namespace sgnlf::field
