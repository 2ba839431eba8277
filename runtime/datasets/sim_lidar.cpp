#include "datasets/sim_lidar.hpp"

#include <algorithm>
#include <cmath>
#include <thread>

#include "core/error.hpp"
#include "core/rng.hpp"

namespace sgnlf::sim {

void DropStats::add(const DropStats& o) {
  rays += o.rays; returns += o.returns; no_hit += o.no_hit; out_of_range += o.out_of_range;
  grazing += o.grazing; weak += o.weak; specular += o.specular; random += o.random; ego += o.ego;
  dark += o.dark; burst += o.burst; far += o.far;
}

void LidarModel::validate() const {
  const std::string w = "lidar model";
  check_range(w, "beam_gain_sigma", beam_gain_sigma, 0.0, 3.0);
  check_range(w, "dark_drop", dark_drop, 0.0, 1.0);
  check_range(w, "burst_drop", burst_drop, 0.0, 1.0);
  check_range(w, "burst_columns", burst_columns, 1, 100000);
  check_range(w, "far_drop", far_drop, 0.0, 1.0);
  check_range(w, "random_drop", random_drop, 0.0, 1.0);
  check_range(w, "ego_top_m", ego_top_m, 0.0, 10.0);
}

BeamPattern beam_pattern(const Sensor& s, const std::string& beams) {
  BeamPattern b;
  if (beams == "native" && s.name == "kitti360") {
    // HDL-64E: upper block 32 lasers +2° … −8.33° (1/3° apart), lower block 32 lasers
    // −8.83° … −24.33° (1/2° apart); 0.1728° azimuth steps at 10 Hz.
    for (int k = 0; k < 32; ++k) b.elevation_deg.push_back(2.0 - k / 3.0);
    for (int k = 0; k < 32; ++k) b.elevation_deg.push_back(-8.83 - 0.5 * k);
    b.azimuth_steps = 2083;
  } else if (beams == "native" && s.name == "nuscenes") {
    // HDL-32E: 32 lasers +10.67° … −30.67° (4/3° apart); 0.33° azimuth steps at 20 Hz.
    for (int k = 0; k < 32; ++k) b.elevation_deg.push_back(10.67 - k * 4.0 / 3.0);
    b.azimuth_steps = 1084;
  } else if (beams == "native" || beams == "grid") {
    b.grid = true;
    b.azimuth_steps = s.width;
    for (int r = 0; r < s.height; ++r) b.elevation_deg.push_back(s.fov_up_deg - r * s.fov_deg / s.height);
  } else {
    throw ConfigError("lidar model: beams '" + beams + "' (expected native or grid)");
  }
  return b;
}

namespace {

double unit(uint32_t x) { return (double(x) + 0.5) * (1.0 / 4294967296.0); }

// Ego car body in the LiDAR frame (sensor on the roof): rays into it return nothing.
bool hits_ego(const Eigen::Vector3f& d, float sensor_height, const LidarModel& m) {
  const float lo[3] = {-float(m.ego_back_m), -float(m.ego_half_width_m), -sensor_height},
              hi[3] = {float(m.ego_front_m), float(m.ego_half_width_m), -float(m.ego_top_m)};
  float t0 = 0.f, t1 = 1e30f;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < 1e-9f) { if (0.f < lo[a] || 0.f > hi[a]) return false; continue; }
    float ta = lo[a] / d[a], tb = hi[a] / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t0 <= t1;
}

RayReturn cast_pixel(const Scene& scene, const Sensor& s, const Pose& T, const LidarModel& m,
                    uint64_t seed, uint32_t frame, int row, int width, int col,
                    const Eigen::Vector3f& d_l, double beam_gain, DropStats& st) {
  RayReturn out;
  ++st.rays;
  if (m.ego_vehicle && hits_ego(d_l, float(T.translation().z() - scene.ground_z), m)) { ++st.ego; return out; }
  const bool real = m.noise && m.realistic_drop();
  if (real && m.burst_drop > 0) {  // one draw per (laser, block of azimuth steps)
    const int blocks = (width + m.burst_columns - 1) / m.burst_columns;
    const auto b = philox_block(seed, 3000u + frame, uint64_t(row) * uint64_t(blocks) + uint64_t(col / m.burst_columns));
    if (unit(b[0]) < m.burst_drop) { ++st.burst; return out; }
  }
  const V3 o = T.translation().cast<float>();
  const V3 d = (T.linear().cast<float>() * d_l).normalized();
  Hit h;
  const float t_max = float(s.max_range_m) + 1.0f;
  if (!scene.cast(o, d, t_max, h)) { ++st.no_hit; return out; }
  const auto rnd = philox_block(seed, 1000u + frame, uint64_t(row) * uint64_t(width) + uint64_t(col));
  // Two normals by Box–Muller from words 0, 1; words 2, 3 drive the drop decisions.
  const double rr = std::sqrt(-2.0 * std::log(unit(rnd[0]))), ang = 2 * M_PI * unit(rnd[1]);
  const double n_range = m.noise ? rr * std::cos(ang) : 0.0, n_int = m.noise ? rr * std::sin(ang) : 0.0;
  const double u_drop = unit(rnd[2]), u_weak = unit(rnd[3]);
  const double cos_i = std::abs(double(h.normal.dot(d)));
  double r = double(h.t) + n_range * (m.range_noise_m + m.range_noise_rel * h.t);
  if (!(r < s.max_range_m) || r <= s.min_range_m) { ++st.out_of_range; return out; }
  // Grazing incidence: the return fades out linearly below grazing_cos.
  if (cos_i < m.grazing_cos * (m.noise ? u_weak : 1.0)) { ++st.grazing; return out; }
  const double power = beam_gain * h.reflectance * cos_i * (100.0 / (r * r));
  if (power < m.weak_power * (m.noise ? 0.5 + u_weak : 1.0)) { ++st.weak; return out; }
  if (m.noise) {
    double p_spec = 0;
    if (h.material == Material::glass || h.material == Material::car_glass) p_spec = m.glass_drop;
    if (h.material == Material::foliage) p_spec = m.foliage_drop;
    if (u_drop < p_spec) { ++st.specular; return out; }
    if (u_drop > 1.0 - m.random_drop) { ++st.random; return out; }
  }
  if (real) {  // the real-scan causes, from their own stream
    const auto q = philox_block(seed, 2000u + frame, uint64_t(row) * uint64_t(width) + uint64_t(col));
    const double p_dark = m.dark_drop * std::max(0.0, 1.0 - h.reflectance / 0.3);
    if (unit(q[0]) < p_dark) { ++st.dark; return out; }
    if (unit(q[1]) < m.far_drop * r / s.max_range_m) { ++st.far; return out; }
  }
  // Intensity: reflectance, Lambert-like incidence, mild range attenuation, additive noise.
  const double inten = m.intensity_gain * h.reflectance * (m.intensity_ambient + (1.0 - m.intensity_ambient) * cos_i) *
                           std::exp(-r / 250.0) + m.intensity_noise * n_int;
  const Eigen::Vector3f p = d_l * float(r);
  out.ret = true;
  out.p = {p.x(), p.y(), p.z(), float(std::clamp(inten, 0.0, 0.99))};
  out.label = h.label;
  ++st.returns;
  return out;
}

}  // namespace

Eigen::Vector3f beam_direction(const Sensor& s, const BeamPattern& bp, int row, int col) {
  if (bp.grid) return pixel_direction(s, row, col);
  // Azimuth of step `col` measured like protocol §1 (β = π − col·2π/N), so that step k
  // sweeps the range-image columns in order.
  const int cols = bp.azimuth_steps;
  const double beta = M_PI - (col + 0.5) * 2.0 * M_PI / cols, alpha = bp.elevation_deg[size_t(row)] * M_PI / 180.0;
  return Eigen::Vector3f(float(std::cos(alpha) * std::cos(beta)), float(std::cos(alpha) * std::sin(beta)),
                         float(std::sin(alpha)));
}

void cast_columns(const Scene& scene, const Sensor& s, const BeamPattern& bp, const LidarModel& model,
                  uint64_t seed, uint32_t frame, const std::vector<int>& columns,
                  const std::vector<Pose>& T_world_lidar_of_column, int threads,
                  std::vector<RayReturn>& out, DropStats& stats) {
  const int rows = int(bp.elevation_deg.size()), cols = bp.azimuth_steps;
  require(out.size() == size_t(rows) * size_t(cols) && T_world_lidar_of_column.size() == size_t(cols),
          "cast_columns: buffers do not match the beam pattern");
  if (threads <= 0) threads = int(std::max(1u, std::thread::hardware_concurrency()));
  threads = std::min(threads, rows);
  // Laser gains (a property of the head: one draw per laser, the same in every frame).
  std::vector<double> gain(size_t(rows), 1.0);
  if (model.noise && model.beam_gain_sigma > 0)
    for (int row = 0; row < rows; ++row) {
      const auto g = philox_block(seed, 4000u, uint64_t(row));
      const double n = std::sqrt(-2.0 * std::log(unit(g[0]))) * std::cos(2 * M_PI * unit(g[1]));
      gain[size_t(row)] = std::exp(model.beam_gain_sigma * n);
    }
  std::vector<DropStats> st(static_cast<size_t>(threads), DropStats{});
  auto work = [&](int k) {
    for (int row = k; row < rows; row += threads)  // interleaved rows balance the load
      for (int col : columns)
        out[size_t(row) * cols + col] = cast_pixel(scene, s, T_world_lidar_of_column[size_t(col)], model, seed, frame,
                                                   row, cols, col, beam_direction(s, bp, row, col),
                                                   gain[size_t(row)], st[size_t(k)]);
  };
  std::vector<std::thread> pool;
  for (int k = 1; k < threads; ++k) pool.emplace_back(work, k);
  work(0);
  for (auto& t : pool) t.join();
  for (const auto& x : st) stats.add(x);
}

std::vector<PointXYZI> collect_returns(const std::vector<RayReturn>& rays) {
  std::vector<PointXYZI> pts;
  for (const auto& p : rays)
    if (p.ret) pts.push_back(p.p);
  return pts;
}

std::vector<uint16_t> collect_labels(const std::vector<RayReturn>& rays) {
  std::vector<uint16_t> labels;
  for (const auto& p : rays)
    if (p.ret) labels.push_back(p.label);
  return labels;
}

std::vector<PointXYZI> cast_scan(const Scene& scene, const Sensor& s, const Pose& T_world_lidar,
                                 const LidarModel& model, uint64_t seed, uint32_t frame, int threads,
                                 DropStats* stats, std::vector<uint16_t>* labels) {
  const BeamPattern bp = beam_pattern(s, model.beams);
  const int rows = int(bp.elevation_deg.size()), cols = bp.azimuth_steps;
  std::vector<RayReturn> px(size_t(rows) * cols);
  std::vector<int> columns(static_cast<size_t>(cols));
  for (int c = 0; c < cols; ++c) columns[size_t(c)] = c;
  DropStats st;
  cast_columns(scene, s, bp, model, seed, frame, columns, std::vector<Pose>(size_t(cols), T_world_lidar), threads,
               px, st);
  if (stats) stats->add(st);
  if (labels) *labels = collect_labels(px);
  return collect_returns(px);
}

}  // namespace sgnlf::sim
