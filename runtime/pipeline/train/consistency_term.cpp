// ConsistencyTerm (consistency_term.hpp).
#include "pipeline/train/consistency_term.hpp"

#include <cmath>

#include "core/error.hpp"
#include "geometry/range_image.hpp"
#include "render/pose_gradient.hpp"

namespace sgnlf::pipeline {

ConsistencyTerm::ConsistencyTerm(cl::Runtime& rt, const Scene& scene,
                                 const ConsistencyConfig& cfg, int max_rays)
    : cfg_(fit_consistency_to_sensor(cfg, scene.sensor)),
      sensor_i_(consistency_render_sensor(cfg_, scene.sensor)),
      sensor_j_(consistency_image_sensor(cfg_, scene.sensor)),
      scale_(scene.norm.scale),
      dirs_i_(ray_directions(sensor_i_)) {
  const int n_i = sensor_i_.height * sensor_i_.width;
  if (n_i > max_rays)
    throw ConfigError("config.consistency: the render grid render_rows × render_cols = " +
                      std::to_string(n_i) + " rays exceeds the model's ray capacity " +
                      std::to_string(max_rays) + " (max of rays_per_batch, render_chunk_rays)");
  // Frame j's observed image on the image sub-sensor: every stride-th row and column.
  const int H = scene.sensor.height, W = scene.sensor.width;
  const int h = sensor_j_.height, w = sensor_j_.width;
  observed_m_.resize(scene.images.size());
  for (size_t f = 0; f < scene.images.size(); ++f) {
    const RangeImage& img = scene.images[f];
    require(img.height == H && img.width == W, "ConsistencyTerm: frame image size differs from the sensor");
    auto& o = observed_m_[f];
    o.resize(size_t(h) * size_t(w));
    for (int r = 0; r < h; ++r)
      for (int c = 0; c < w; ++c)
        o[size_t(r) * w + c] =
            float(img.range[img.idx(r * cfg_.image_row_stride, c * cfg_.image_col_stride)] / scale_);
  }
  reproj_ = std::make_unique<render::CrossFrameReprojection>(rt, sensor_i_, sensor_j_, scale_);
  out_ = reproj_->make_output();
  // cfg_'s discriminator is fitted to the h × w image sub-sensor (fit_consistency_to_sensor).
  disc_ = std::make_unique<adversarial::PatchDiscriminator>(rt, cfg_.discriminator);
  const size_t n_j = size_t(h) * size_t(w);
  depth_i_ = cl::Buffer(rt, size_t(n_i) * 4), grad_depth_i_ = cl::Buffer(rt, size_t(n_i) * 4);
  grad_range_ = cl::Buffer(rt, n_j * 4);
  real_m_ = cl::Buffer(rt, n_j * 8), fake_m_ = cl::Buffer(rt, n_j * 8);
  d_fake_m_ = cl::Buffer(rt, n_j * 8);
}

ConsistencyResult ConsistencyTerm::run(FieldPass& field, const ConsistencyPair& p,
                                       bool train_discriminator, bool pose_grads) {
  ConsistencyResult res;
  const int n_i = sensor_i_.height * sensor_i_.width;
  const int h = sensor_j_.height, w = sensor_j_.width;
  const size_t n_j = size_t(h) * size_t(w);
  // Frame i's rays from its current pose (normalised frame).
  const Pose T_world_lidar_i = corrected_pose(p.T_init_i, p.xi_i);
  const Pose T_world_lidar_j = corrected_pose(p.T_init_j, p.xi_j);
  const Eigen::Matrix3f R = T_world_lidar_i.rotation().cast<float>();
  const Eigen::Vector3f t = T_world_lidar_i.translation().cast<float>();
  std::vector<float> o(size_t(n_i) * 3), d(size_t(n_i) * 3);
  for (int k = 0; k < n_i; ++k) {
    const Eigen::Vector3f dw = R * Eigen::Vector3f(dirs_i_[3 * size_t(k)], dirs_i_[3 * size_t(k) + 1],
                                                   dirs_i_[3 * size_t(k) + 2]);
    for (int a = 0; a < 3; ++a) o[3 * size_t(k) + a] = t[a], d[3 * size_t(k) + a] = dw[a];
  }
  const RenderedRays rays = field.render(o, d, n_i);
  const std::vector<float>& out = rays.out;
  std::vector<float> depth(static_cast<size_t>(n_i), 0.0f);
  for (int k = 0; k < n_i; ++k) {
    const bool hit = out[3 * size_t(k) + 1] > float(cfg_.return_threshold);
    depth[size_t(k)] = hit ? out[3 * size_t(k)] : 0.0f;
    res.rendered_points += hit ? 1 : 0;
  }
  depth_i_.write_vec(depth);
  // D_ij, M_ij on frame j's image sub-sensor.
  const render::ReprojectionContext ctx =
      reproj_->forward(depth_i_, T_world_lidar_i, T_world_lidar_j, out_);
  last_img_ = reproj_->read(out_);
  const render::ReprojectionImages& img = last_img_;
  const std::vector<float>& Dj = observed_m_.at(size_t(p.j));
  const float inv = float(1.0 / scale_);
  std::vector<float> fake(2 * n_j), real(2 * n_j);
  double covered = 0.0;
  for (size_t q = 0; q < n_j; ++q) {
    fake[2 * q] = img.range[q] * inv;
    real[2 * q] = img.mask[q] * Dj[q];
    fake[2 * q + 1] = real[2 * q + 1] = Dj[q];
    covered += img.mask[q];
  }
  res.coverage = covered / double(n_j);
  fake_m_.write_vec(fake);
  real_m_.write_vec(real);
  if (train_discriminator) {
    disc_->step(real_m_, fake_m_, 1, h, w);
    res.l_d = disc_->read_losses().d_total();
    // The step's forward held [real, fake]: mean logit of each, averaged over scales.
    for (int s = 0; s < cfg_.discriminator.scales; ++s) {
      const auto lg = disc_->read_logits(s);
      const size_t half = lg.size() / 2;
      double a = 0.0, b = 0.0;
      for (size_t k = 0; k < half; ++k) a += lg[k], b += lg[half + k];
      res.d_real_mean += a / double(half) / cfg_.discriminator.scales;
      res.d_fake_mean += b / double(half) / cfg_.discriminator.scales;
    }
  }
  // Generator term and dL_con/dD_ij (per metre → per normalised depth unit), weighted by λ_con.
  disc_->generator_grad(fake_m_, 1, h, w, d_fake_m_);
  res.l_con = disc_->read_losses().con;
  if (!std::isfinite(res.l_con))
    throw NumericError("consistency term: L_con not finite at step " + std::to_string(field.step) +
                       " (pair " + std::to_string(p.i) + " → " + std::to_string(p.j) + ")");
  const std::vector<float> d_fake = d_fake_m_.read_vec<float>(2 * n_j);
  std::vector<float> grad_range(n_j);
  const float k_range = float(cfg_.weight) * inv;
  for (size_t q = 0; q < n_j; ++q) grad_range[q] = d_fake[2 * q] * k_range;
  grad_range_.write_vec(grad_range);
  const render::ReprojectionPoseGradient pg = reproj_->backward(
      ctx, depth_i_, out_, grad_range_, grad_depth_i_, p.xi_i, p.xi_j);
  // Frame i's depths → the field (this step's gradient), and its rays → ξ_i.
  const std::vector<float> g_depth = grad_depth_i_.read_vec<float>(size_t(n_i));
  std::vector<float> g_out(size_t(n_i) * 3, 0.0f);
  for (int k = 0; k < n_i; ++k) g_out[3 * size_t(k)] = g_depth[size_t(k)];
  const RayGrads rg = field.backward(rays, g_out, pose_grads);
  if (pose_grads) {
    res.grad_xi_i = pg.xi_i + render::pose_gradient(p.T_init_i, p.xi_i, {}, dirs_i_, rg.origin,
                                                    rg.direction);
    res.grad_xi_j = pg.xi_j;
  }
  return res;
}

}  // namespace sgnlf::pipeline
