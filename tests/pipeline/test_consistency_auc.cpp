// Can the PatchGAN discriminator see a misalignment? Frame i's OBSERVED
// range image reprojected into frame j (render::CrossFrameReprojection) under the ground-truth
// poses gives aligned pairs [D_ij, D_j]; under frame i's pose moved by 0.5 m (random direction)
// or turned by 2° (random axis), misaligned ones. A discriminator trained briefly with the
// aligned pairs of the first frames as real and misaligned ones as fake separates the held-out
// later frames' pairs: AUC of the mean logit ≥ 0.9. Simulator frames, fixed seeds.
#include <catch2/catch.hpp>

#include <cmath>

#include "adversarial/patch_discriminator.hpp"
#include "core/rng.hpp"
#include "datasets/simulate.hpp"
#include "render/cross_frame_reprojection.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

namespace {

const Dataset& auc_dataset() {
  static const Dataset d = [] {
    SimOptions o;
    o.sequence = "kitti360-1538";
    o.frames = 24;
    o.height = 32;
    o.width = 256;
    o.threads = 1;
    return simulate(o).dataset;
  }();
  return d;
}

Eigen::Vector3d random_unit(Rng& rng) {
  Eigen::Vector3d v(rng.normal(), rng.normal(), rng.normal());
  return v.normalized();
}

// Pair image [D_ij, D_j] (metres, h × w × 2) of frame i's observed depths under T_world_lidar_i.
std::vector<float> pair_image(render::CrossFrameReprojection& rp, cl::Runtime& rt, const Dataset& d,
                              int i, const Pose& T_world_lidar_i) {
  const int j = i + 1;
  cl::Buffer depth = cl::Buffer::from(rt, d.frames[size_t(i)].image.range);
  render::ReprojectionOutput out = rp.make_output();
  rp.forward(depth, T_world_lidar_i, d.frames[size_t(j)].T_world_lidar, out);
  const render::ReprojectionImages img = rp.read(out);
  const std::vector<float>& Dj = d.frames[size_t(j)].image.range;
  std::vector<float> pair(2 * Dj.size());
  for (size_t q = 0; q < Dj.size(); ++q) pair[2 * q] = img.range[q], pair[2 * q + 1] = Dj[q];
  return pair;
}

double auc(const std::vector<double>& pos, const std::vector<double>& neg) {
  double s = 0.0;
  for (double p : pos)
    for (double n : neg) s += p > n ? 1.0 : (p == n ? 0.5 : 0.0);
  return s / double(pos.size() * neg.size());
}

}  // namespace

TEST_CASE("discriminator separates aligned from misaligned reprojected pairs (AUC >= 0.9)",
          "[pipeline][consistency][adversarial][device]") {
  cl::Runtime& rt = test::runtime();
  const Dataset& d = auc_dataset();
  const int h = d.sensor.height, w = d.sensor.width;
  render::CrossFrameReprojection rp(rt, d.sensor, d.sensor, 1.0);
  // Per pair (i, i+1): the aligned image and two misaligned ones (0.5 m, 2°).
  std::vector<std::vector<float>> aligned, misaligned;
  std::vector<int> pair_of;  // misaligned image → pair index
  Rng rng(11, 0xa0c);
  const int n_pairs = int(d.frames.size()) - 1;
  for (int i = 0; i < n_pairs; ++i) {
    const Pose& T = d.frames[size_t(i)].T_world_lidar;
    aligned.push_back(pair_image(rp, rt, d, i, T));
    Pose shifted = Pose::Identity(), turned = Pose::Identity();
    shifted.translation() = 0.5 * random_unit(rng);
    turned.linear() = Eigen::AngleAxisd(2.0 * M_PI / 180.0, random_unit(rng)).toRotationMatrix();
    misaligned.push_back(pair_image(rp, rt, d, i, T * shifted));
    misaligned.push_back(pair_image(rp, rt, d, i, T * turned));
    pair_of.push_back(i), pair_of.push_back(i);
  }
  const int n_train = 14;  // pairs (0,1) … (13,14) train; (14,15) … (22,23) are held out

  adversarial::PatchDiscriminatorConfig cfg;  // the method's architecture (method.md §4.3)
  cfg.lr = 1e-3f;
  adversarial::PatchDiscriminator disc(rt, cfg);
  const int batch = 8;
  const size_t img = size_t(h) * size_t(w) * 2;
  cl::Buffer real(rt, batch * img * 4), fake(rt, batch * img * 4);
  Rng pick(12, 0xa0d);
  for (int s = 0; s < 80; ++s) {
    std::vector<float> r, f;
    for (int k = 0; k < batch; ++k) {
      const auto& a = aligned[pick.below(uint32_t(n_train))];
      const auto& m = misaligned[pick.below(uint32_t(2 * n_train))];
      r.insert(r.end(), a.begin(), a.end());
      f.insert(f.end(), m.begin(), m.end());
    }
    real.write_vec(r);
    fake.write_vec(f);
    disc.step(real, fake, batch, h, w);
  }
  // Held-out scores: mean logit per image over its patches, averaged over the scales.
  auto score = [&](const std::vector<float>& image) {
    cl::Buffer b = cl::Buffer::from(rt, image);
    disc.forward(b, 1, h, w);
    double s = 0.0;
    for (int sc = 0; sc < cfg.scales; ++sc) {
      const auto lg = disc.read_logits(sc);
      double m = 0.0;
      for (float v : lg) m += v;
      s += m / double(lg.size()) / cfg.scales;
    }
    return s;
  };
  std::vector<double> pos, neg;
  for (int i = n_train; i < n_pairs; ++i) pos.push_back(score(aligned[size_t(i)]));
  for (size_t k = 0; k < misaligned.size(); ++k)
    if (pair_of[k] >= n_train) neg.push_back(score(misaligned[k]));
  const double a = auc(pos, neg);
  INFO("held-out AUC " << a << " (" << pos.size() << " aligned, " << neg.size() << " misaligned)");
  CHECK(a >= 0.9);
}
