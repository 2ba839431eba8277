// Host references of the scene-flow field and the composite LiDAR4D encoder (tests only).
#include "lidar4d_reference.hpp"

#include <algorithm>

#include "reference.hpp"
#include "reference_4d.hpp"

namespace sgnlf::test::ref {
namespace {
double basis(int j, int nodes, double t) {
  double w = 1.0;
  for (int m = 0; m < nodes; ++m)
    if (m != j) w *= (t - double(m) / (nodes - 1)) / (double(j - m) / (nodes - 1));
  return w;
}
std::vector<float> slice_of(const std::vector<float>& v, size_t begin, size_t count) {
  return {v.begin() + long(begin), v.begin() + long(begin + count)};
}
}  // namespace

std::vector<float> lagrange_fwd(int levels, int features, int nodes, const std::vector<float>& in,
                                const std::vector<float>& t) {
  const int g = features / nodes, n = int(t.size());
  std::vector<float> out(size_t(n) * levels * g);
  for (int i = 0; i < n; ++i)
    for (int l = 0; l < levels; ++l)
      for (int c = 0; c < g; ++c) {
        double s = 0;
        for (int j = 0; j < nodes; ++j)
          s += basis(j, nodes, t[size_t(i)]) *
               in[(size_t(i) * levels + l) * features + size_t(j * g + c)];
        out[(size_t(i) * levels + l) * g + c] = float(s);
      }
  return out;
}

std::vector<float> lagrange_bwd(int levels, int features, int nodes,
                                const std::vector<float>& d_out, const std::vector<float>& t) {
  const int g = features / nodes, n = int(t.size());
  std::vector<float> d_in(size_t(n) * levels * features);
  for (int i = 0; i < n; ++i)
    for (int l = 0; l < levels; ++l)
      for (int j = 0; j < nodes; ++j)
        for (int c = 0; c < g; ++c)
          d_in[(size_t(i) * levels + l) * features + size_t(j * g + c)] =
              float(basis(j, nodes, t[size_t(i)]) * d_out[(size_t(i) * levels + l) * g + c]);
  return d_in;
}

std::vector<float> scene_flow_fwd(const field::SceneFlowConfig& cfg,
                                  const std::vector<float>& slice,
                                  const std::vector<float>& x, const std::vector<float>& t) {
  const auto gc = cfg.grid_config();
  const auto lv = field::hash_grid_levels(gc);
  const size_t grid_n = (size_t(lv.back().offset) + lv.back().size) * size_t(gc.features);
  const std::vector<float> ones(size_t(gc.levels), 1.0f);
  const auto g = hashgrid_fwd(gc, slice_of(slice, 0, grid_n), x, ones);
  const auto in = lagrange_fwd(cfg.levels, cfg.features, cfg.time_nodes, g, t);
  return mlp_fwd(field::scene_flow_mlp_spec(cfg), slice_of(slice, grid_n, slice.size() - grid_n), in,
                 int(t.size()));
}

void scene_flow_bwd(const field::SceneFlowConfig& cfg, const std::vector<float>& slice,
                    const std::vector<float>& x, const std::vector<float>& t,
                    const std::vector<float>& d_flow, std::vector<float>& grad,
                    std::vector<float>& d_x) {
  const auto gc = cfg.grid_config();
  const auto lv = field::hash_grid_levels(gc);
  const size_t grid_n = (size_t(lv.back().offset) + lv.back().size) * size_t(gc.features);
  const std::vector<float> ones(size_t(gc.levels), 1.0f);
  const auto table = slice_of(slice, 0, grid_n);
  const auto g = hashgrid_fwd(gc, table, x, ones);
  const auto in = lagrange_fwd(cfg.levels, cfg.features, cfg.time_nodes, g, t);
  std::vector<float> d_in;
  const auto spec = field::scene_flow_mlp_spec(cfg);
  auto g_mlp = mlp_bwd(spec, slice_of(slice, grid_n, slice.size() - grid_n), in, int(t.size()),
                       d_flow, d_in);
  // Bias-free: the bias rows (after each layer's n_in rows) receive no gradient.
  size_t at = 0;
  for (size_t l = 0; l < spec.layers.size(); ++l) {
    const size_t n_in = size_t(l == 0 ? spec.n_in : spec.layers[l - 1].width);
    const size_t pad = size_t(field::Mlp::pad16(spec.layers[l].width));
    for (size_t o = 0; o < pad; ++o) g_mlp[at + n_in * pad + o] = 0.0f;
    at += (n_in + 1) * pad;
  }
  const auto d_g = lagrange_bwd(cfg.levels, cfg.features, cfg.time_nodes, d_in, t);
  grad = hashgrid_bwd(gc, grid_n, x, ones, d_g);
  grad.insert(grad.end(), g_mlp.begin(), g_mlp.end());
  d_x = hashgrid_bwd_dx(gc, table, x, ones, d_g);
}

std::vector<float> lidar4d_fwd(const field::Lidar4DEncoderConfig& cfg,
                               const field::Lidar4DParamOffsets& off,
                               const std::vector<float>& slice, const std::vector<float>& x,
                               const TimeState& ts) {
  using field::PlaneGroups;
  const size_t n = x.size() / 3;
  const auto planes = slice_of(slice, off.planes, off.static_hash - off.planes);
  const auto shash = slice_of(slice, off.static_hash, off.time_hash - off.static_hash);
  const auto thash = slice_of(slice, off.time_hash, off.flow - off.time_hash);
  const auto flow_p = slice_of(slice, off.flow, off.end - off.flow);
  const std::vector<float> t(n, ts.t), ones(size_t(cfg.static_hash.levels), 1.0f);
  const auto ps = kplanes_fwd(cfg.planes, planes, x, t, PlaneGroups::Static);
  const auto hs = hashgrid_fwd(cfg.static_hash, shash, x, ones);
  // The dynamic features f at (positions, time).
  auto dyn = [&](const std::vector<float>& xs, float tv) {
    const std::vector<float> tt(n, tv);
    const auto pd = kplanes_fwd(cfg.planes, planes, xs, tt, PlaneGroups::Dynamic);
    const auto hd = time_hash_fwd(cfg.time_hash, thash, xs, tt);
    const size_t wp = pd.size() / n, wh = hd.size() / n;
    std::vector<double> out;
    for (size_t i = 0; i < n; ++i) {
      for (size_t c = 0; c < wp; ++c) out.push_back(pd[i * wp + c]);
      for (size_t c = 0; c < wh; ++c) out.push_back(hd[i * wh + c]);
    }
    return out;
  };
  auto d = dyn(x, ts.t);
  const size_t wd = d.size() / n;
  const bool next = cfg.blend && ts.has_next && ts.dt > 0;
  const bool prev = cfg.blend && ts.has_prev && ts.dt > 0;
  if (next || prev) {
    const auto flow = scene_flow_fwd(cfg.flow, flow_p, x, t);
    const double w1 = next ? 0.25 : 0.0, w2 = prev ? 0.25 : 0.0, w0 = 1.0 - w1 - w2;
    for (auto& v : d) v *= w0;
    for (int side = 0; side < 2; ++side) {
      if (side == 0 ? !next : !prev) continue;
      std::vector<float> xn(x.size());
      for (size_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) xn[i * 3 + k] = x[i * 3 + k] + flow[i * 6 + side * 3 + k];
      const float tn = side == 0 ? std::min(1.0f, ts.t + ts.dt) : std::max(0.0f, ts.t - ts.dt);
      const auto f = dyn(xn, tn);
      for (size_t k = 0; k < d.size(); ++k) d[k] += 0.25 * f[k];
    }
  }
  const size_t wp = ps.size() / n, wh = hs.size() / n;
  std::vector<float> out;
  for (size_t i = 0; i < n; ++i) {
    for (size_t c = 0; c < wp; ++c) out.push_back(ps[i * wp + c]);
    for (size_t c = 0; c < wh; ++c) out.push_back(hs[i * wh + c]);
    for (size_t c = 0; c < wd; ++c) out.push_back(float(d[i * wd + c]));
  }
  return out;
}

field::Lidar4DEncoderConfig small_lidar4d_config(float flow_std) {
  field::Lidar4DEncoderConfig c;
  c.planes.resolution = 5;
  c.planes.scales = 2;
  c.planes.time_resolution = 3;
  c.planes.features = 2;
  c.static_hash.levels = 3;
  c.static_hash.features = 2;
  c.static_hash.log2_table_size = 8;
  c.static_hash.base_resolution = 4.0f;
  c.static_hash.per_level_scale = 2.0f;
  c.time_hash.levels = 2;
  c.time_hash.features = 2;
  c.time_hash.base_resolution = 4.0f;
  c.time_hash.per_level_scale = 2.0f;
  c.time_hash.log2_table_xy = 7;
  c.time_hash.log2_table_xz = 6;
  c.time_hash.log2_table_yz = 6;
  c.time_hash.time_slices = 4;
  c.flow.levels = 2;
  c.flow.features = 4;
  c.flow.time_nodes = 2;
  c.flow.base_resolution = 4.0f;
  c.flow.max_resolution = 8.0f;
  c.flow.log2_table_size = 8;
  c.flow.hidden_width = 16;
  c.flow.hidden_layers = 1;
  c.flow.out_init_std = flow_std;
  return c;
}

}  // namespace sgnlf::test::ref
