#include "datasets/sim_lidar.hpp"

#include <algorithm>
#include <cmath>
#include <thread>

#include "core/rng.hpp"

namespace sgnlf::sim {

void DropStats::add(const DropStats& o) {
  rays += o.rays; returns += o.returns; no_hit += o.no_hit; out_of_range += o.out_of_range;
  grazing += o.grazing; weak += o.weak; specular += o.specular; random += o.random;
}

namespace {

struct PixelOut {
  bool ret = false;
  PointXYZI p{0, 0, 0, 0};
};

double unit(uint32_t x) { return (double(x) + 0.5) * (1.0 / 4294967296.0); }

PixelOut cast_pixel(const Scene& scene, const Sensor& s, const Pose& T, const LidarModel& m,
                    uint64_t seed, uint32_t frame, int row, int col, DropStats& st) {
  PixelOut out;
  ++st.rays;
  const Eigen::Vector3f d_l = pixel_direction(s, row, col);
  const V3 o = T.translation().cast<float>();
  const V3 d = (T.linear().cast<float>() * d_l).normalized();
  Hit h;
  const float t_max = float(s.max_range_m) + 1.0f;
  if (!scene.cast(o, d, t_max, h)) { ++st.no_hit; return out; }
  const auto rnd = philox_block(seed, 1000u + frame, uint64_t(row) * uint64_t(s.width) + uint64_t(col));
  // Two normals by Box–Muller from words 0, 1; words 2, 3 drive the drop decisions.
  const double rr = std::sqrt(-2.0 * std::log(unit(rnd[0]))), ang = 2 * M_PI * unit(rnd[1]);
  const double n_range = m.noise ? rr * std::cos(ang) : 0.0, n_int = m.noise ? rr * std::sin(ang) : 0.0;
  const double u_drop = unit(rnd[2]), u_weak = unit(rnd[3]);
  const double cos_i = std::abs(double(h.normal.dot(d)));
  double r = double(h.t) + n_range * (m.range_noise_m + m.range_noise_rel * h.t);
  if (!(r < s.max_range_m) || r <= s.min_range_m) { ++st.out_of_range; return out; }
  // Grazing incidence: the return fades out linearly below grazing_cos.
  if (cos_i < m.grazing_cos * (m.noise ? u_weak : 1.0)) { ++st.grazing; return out; }
  const double power = h.reflectance * cos_i * (100.0 / (r * r));
  if (power < m.weak_power * (m.noise ? 0.5 + u_weak : 1.0)) { ++st.weak; return out; }
  if (m.noise) {
    double p_spec = 0;
    if (h.material == Material::glass || h.material == Material::car_glass) p_spec = m.glass_drop;
    if (h.material == Material::foliage) p_spec = m.foliage_drop;
    if (u_drop < p_spec) { ++st.specular; return out; }
    if (u_drop > 1.0 - m.random_drop) { ++st.random; return out; }
  }
  // Intensity: reflectance, Lambert-like incidence, mild range attenuation, additive noise.
  const double inten = h.reflectance * (0.45 + 0.55 * cos_i) * std::exp(-r / 250.0) + m.intensity_noise * n_int;
  const Eigen::Vector3f p = d_l * float(r);
  out.ret = true;
  out.p = {p.x(), p.y(), p.z(), float(std::clamp(inten, 0.0, 0.99))};
  ++st.returns;
  return out;
}

}  // namespace

std::vector<PointXYZI> cast_scan(const Scene& scene, const Sensor& s, const Pose& T_world_lidar,
                                 const LidarModel& model, uint64_t seed, uint32_t frame, int threads,
                                 DropStats* stats) {
  if (threads <= 0) threads = int(std::max(1u, std::thread::hardware_concurrency()));
  threads = std::min(threads, s.height);
  std::vector<PixelOut> px(size_t(s.height) * s.width);
  std::vector<DropStats> st(static_cast<size_t>(threads), DropStats{});
  auto work = [&](int k) {
    for (int row = k; row < s.height; row += threads)  // interleaved rows balance the load
      for (int col = 0; col < s.width; ++col)
        px[size_t(row) * s.width + col] = cast_pixel(scene, s, T_world_lidar, model, seed, frame, row, col, st[size_t(k)]);
  };
  std::vector<std::thread> pool;
  for (int k = 1; k < threads; ++k) pool.emplace_back(work, k);
  work(0);
  for (auto& t : pool) t.join();
  std::vector<PointXYZI> pts;
  for (const auto& p : px)
    if (p.ret) pts.push_back(p.p);
  if (stats)
    for (const auto& x : st) stats->add(x);
  return pts;
}

}  // namespace sgnlf::sim
