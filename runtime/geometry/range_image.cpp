#include "geometry/range_image.hpp"

#include <cmath>

namespace sgnlf {

Eigen::Vector3f pixel_direction(const Sensor& s, int row, int col) {
  // protocol §1: β = −(i − W/2)/W·2π, α = (fov_up − j·fov/H)·π/180
  const double beta = -(col - s.width / 2.0) / s.width * 2.0 * M_PI;
  const double alpha = (s.fov_up_deg - row * s.fov_deg / s.height) * M_PI / 180.0;
  return Eigen::Vector3f(float(std::cos(alpha) * std::cos(beta)),
                         float(std::cos(alpha) * std::sin(beta)), float(std::sin(alpha)));
}

std::vector<float> ray_directions(const Sensor& s) {
  std::vector<float> d(size_t(s.height) * s.width * 3);
  for (int r = 0; r < s.height; ++r)
    for (int c = 0; c < s.width; ++c) {
      const auto v = pixel_direction(s, r, c);
      const size_t i = (size_t(r) * s.width + c) * 3;
      d[i] = v.x();
      d[i + 1] = v.y();
      d[i + 2] = v.z();
    }
  return d;
}

RangeImage project_points(const Sensor& s, const std::vector<PointXYZI>& pts,
                          ProjectionStats* stats) {
  RangeImage img(s.height, s.width);
  ProjectionStats st;
  const double fov_down = s.fov_deg - s.fov_up_deg;
  const double col_step = 2.0 * M_PI / s.width;
  const double row_step = s.fov_deg * M_PI / 180.0 / s.height;
  for (const auto& p : pts) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) ||
        !std::isfinite(p.intensity)) {
      ++st.non_finite;
      continue;
    }
    const double x = p.x, y = p.y, z = p.z;
    const double rxy = std::sqrt(x * x + y * y);
    const double range = std::sqrt(x * x + y * y + z * z);
    if (!s.in_range(range)) {
      ++(range >= s.max_range_m ? st.beyond_range : st.below_min_range);
      continue;
    }
    const long c = std::lround((M_PI - std::atan2(y, x)) / col_step);
    const long r = std::lround(s.height - (std::atan2(z, rxy) + fov_down * M_PI / 180.0) / row_step);
    if (r < 0 || r >= s.height || c < 0 || c >= s.width) {
      ++st.out_of_fov;
      continue;
    }
    const size_t i = img.idx(int(r), int(c));
    if (img.range[i] > 0.f) {
      ++st.occluded;
      if (img.range[i] <= float(range)) continue;
    } else {
      ++st.projected;
    }
    img.range[i] = float(range);
    img.intensity[i] = p.intensity;
    img.ray_drop[i] = 1.f;
  }
  if (stats) *stats = st;
  return img;
}

std::vector<PointXYZI> unproject(const Sensor& s, const RangeImage& img) {
  std::vector<PointXYZI> out;
  for (int r = 0; r < img.height; ++r)
    for (int c = 0; c < img.width; ++c) {
      const size_t i = img.idx(r, c);
      if (!(img.range[i] > 0.f)) continue;
      const Eigen::Vector3f d = pixel_direction(s, r, c) * img.range[i];
      out.push_back({d.x(), d.y(), d.z(), img.intensity[i]});
    }
  return out;
}

}  // namespace sgnlf
