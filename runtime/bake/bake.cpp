// bake_field (see bake.hpp).
#include "bake/bake.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/log.hpp"

namespace sgnlf::bake {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The world positions of every vertex of the bricks `coords`, n × 3.
std::vector<float> brick_vertices(const BakedScene& s, const std::vector<std::array<int, 3>>& coords) {
  const int n1 = s.brick + 1;
  std::vector<float> x;
  x.reserve(coords.size() * size_t(s.vertices_per_brick()) * 3);
  for (const auto& b : coords)
    for (int k = 0; k < n1; ++k)
      for (int j = 0; j < n1; ++j)
        for (int i = 0; i < n1; ++i) {
          const auto p = s.vertex_position(b, i, j, k);
          for (int a = 0; a < 3; ++a) x.push_back(float(p[size_t(a)]));
        }
  return x;
}

// f over n points in batches.
template <class F>
void batched(int n, int batch, F&& f) {
  for (int b = 0; b < n; b += batch) f(b, std::min(batch, n - b));
}

}  // namespace

Json BakeStats::to_json() const {
  return Json{{"candidate_bricks", candidate_bricks}, {"kept_bricks", kept_bricks},
              {"density_rows", density_rows},         {"head_rows", head_rows},
              {"density_seconds", density_seconds},   {"head_seconds", head_seconds},
              {"seconds", seconds}};
}

BakedScene bake_field(const BakeConfig& cfg, const BakeInput& in, const FieldProbe& probe,
                      BakeStats* stats) {
  cfg.validate();
  const auto t0 = Clock::now();
  const size_t n_ret = in.returns_m.size() / 3;
  if (n_ret == 0) throw ConfigError("bake: the run's training frames have no returns");
  if (in.origins_m.empty()) throw ConfigError("bake: no training sensor origins");
  require(probe.density && probe.head && probe.batch > 0, "bake: incomplete field probe");
  BakedScene s;
  s.voxel_m = cfg.voxel_m;
  s.brick = cfg.brick;
  s.near_m = in.near_m, s.far_m = in.far_m;
  s.step_m = cfg.step();
  s.stop_transmittance = cfg.stop_transmittance;
  // The brick grid over the returns' box grown by the dilation and one brick.
  const double B = s.brick_m(), r = cfg.dilate_m;
  std::array<double, 3> lo, hi;
  lo.fill(std::numeric_limits<double>::max()), hi.fill(-std::numeric_limits<double>::max());
  for (size_t p = 0; p < n_ret; ++p)
    for (size_t a = 0; a < 3; ++a)
      lo[a] = std::min(lo[a], double(in.returns_m[3 * p + a])),
      hi[a] = std::max(hi[a], double(in.returns_m[3 * p + a]));
  double cells = 1.0;
  for (size_t a = 0; a < 3; ++a) {
    s.origin_m[a] = std::floor((lo[a] - r) / B) * B - B;
    s.dims[a] = int(std::ceil((hi[a] + r - s.origin_m[a]) / B)) + 1;
    cells *= s.dims[a];
  }
  if (cells > double(1 << 28))
    throw ConfigError("bake: the brick grid of " + std::to_string(s.dims[0]) + " x " +
                      std::to_string(s.dims[1]) + " x " + std::to_string(s.dims[2]) +
                      " bricks is too large; raise voxel_m or brick");
  const auto at = [&](int i, int j, int k) {
    return (size_t(k) * size_t(s.dims[1]) + size_t(j)) * size_t(s.dims[0]) + size_t(i);
  };
  // Candidates: every brick within dilate_m of a return.
  std::vector<uint8_t> mark(size_t(cells), 0);
  for (size_t p = 0; p < n_ret; ++p) {
    int b0[3], b1[3];
    for (size_t a = 0; a < 3; ++a) {
      b0[a] = int(std::floor((in.returns_m[3 * p + a] - r - s.origin_m[a]) / B));
      b1[a] = int(std::floor((in.returns_m[3 * p + a] + r - s.origin_m[a]) / B));
    }
    for (int k = b0[2]; k <= b1[2]; ++k)
      for (int j = b0[1]; j <= b1[1]; ++j)
        for (int i = b0[0]; i <= b1[0]; ++i) mark[at(i, j, k)] = 1;
  }
  std::vector<std::array<int, 3>> cand;
  for (int k = 0; k < s.dims[2]; ++k)
    for (int j = 0; j < s.dims[1]; ++j)
      for (int i = 0; i < s.dims[0]; ++i)
        if (mark[at(i, j, k)]) cand.push_back({i, j, k});
  if (long(cand.size()) > long(cfg.max_bricks))
    throw ConfigError("bake: " + std::to_string(cand.size()) + " candidate bricks exceed max_bricks " +
                      std::to_string(cfg.max_bricks) + "; raise voxel_m or lower dilate_m");
  BakeStats st;
  st.candidate_bricks = long(cand.size());
  // σ at every candidate vertex.
  const int V = s.vertices_per_brick();
  std::vector<float> logit(cand.size() * size_t(V));
  {
    const auto td = Clock::now();
    const std::vector<float> x = brick_vertices(s, cand);
    const int n = int(logit.size());
    batched(n, probe.batch, [&](int b, int m) {
      const std::vector<float> xs(x.begin() + long(b) * 3, x.begin() + long(b + m) * 3);
      const std::vector<float> l = probe.density(xs, m);
      require(l.size() == size_t(m), "bake: the density probe returned the wrong count");
      std::copy(l.begin(), l.end(), logit.begin() + b);
    });
    st.density_rows = n;
    st.density_seconds = since(td);
  }
  // Keep the bricks where one vertex's σ would stop more than min_alpha over one step.
  const float keep_logit = float(std::log(-std::log1p(-double(std::max(cfg.min_alpha, 1e-12f))) /
                                          double(s.step_m)));
  std::vector<std::array<int, 3>> kept;
  std::vector<size_t> kept_from;
  for (size_t c = 0; c < cand.size(); ++c) {
    const float* l = &logit[c * size_t(V)];
    if (*std::max_element(l, l + V) >= keep_logit) kept.push_back(cand[c]), kept_from.push_back(c);
  }
  st.kept_bricks = long(kept.size());
  s.skip_logit = keep_logit;
  s.index.assign(size_t(cells), -1);
  s.vertices.resize(kept.size() * size_t(V));
  for (size_t q = 0; q < kept.size(); ++q) {
    s.index[at(kept[q][0], kept[q][1], kept[q][2])] = int32_t(q);
    for (int v = 0; v < V; ++v)
      s.vertices[q * size_t(V) + size_t(v)].logit = logit[kept_from[q] * size_t(V) + size_t(v)];
  }
  // The head at every kept vertex, seen from the nearest training origin.
  {
    const auto th = Clock::now();
    const std::vector<float> x = brick_vertices(s, kept);
    const int n = int(s.vertices.size());
    const size_t n_org = in.origins_m.size() / 3;
    batched(n, probe.batch, [&](int b, int m) {
      std::vector<float> xs(x.begin() + long(b) * 3, x.begin() + long(b + m) * 3), dir(size_t(m) * 3);
      for (int p = 0; p < m; ++p) {
        const float* xp = &xs[3 * size_t(p)];
        double best = std::numeric_limits<double>::max();
        size_t o = 0;
        for (size_t q = 0; q < n_org; ++q) {
          double d2 = 0.0;
          for (size_t a = 0; a < 3; ++a) d2 += std::pow(double(xp[a]) - in.origins_m[3 * q + a], 2);
          if (d2 < best) best = d2, o = q;
        }
        double v[3], len = 0.0;
        for (size_t a = 0; a < 3; ++a) v[a] = double(xp[a]) - in.origins_m[3 * o + a], len += v[a] * v[a];
        len = std::sqrt(len);
        for (size_t a = 0; a < 3; ++a)
          dir[3 * size_t(p) + a] = len > 1e-9 ? float(v[a] / len) : (a == 0 ? 1.0f : 0.0f);
      }
      const std::vector<float> h = probe.head(xs, dir, m);
      require(h.size() == size_t(m) * 2, "bake: the head probe returned the wrong count");
      for (int p = 0; p < m; ++p) {
        s.vertices[size_t(b + p)].ret = h[2 * size_t(p)];
        s.vertices[size_t(b + p)].intensity = h[2 * size_t(p) + 1];
      }
    });
    st.head_rows = n;
    st.head_seconds = since(th);
  }
  st.seconds = since(t0);
  log::info("bake: ", st.kept_bricks, " of ", st.candidate_bricks, " candidate bricks kept (",
            s.brick, "^3 cells of ", s.voxel_m, " m), ", double(s.bytes()) / (1 << 20), " MiB, ",
            st.seconds, " s");
  if (stats) *stats = st;
  return s;
}

}  // namespace sgnlf::bake
