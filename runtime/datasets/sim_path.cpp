// Road centreline queries and the ego trajectory along it (see sim_street.hpp).
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/rng.hpp"
#include "datasets/sim_street.hpp"

namespace sgnlf::sim {

namespace {
double wrap_s(const Path& p, double s) {
  const double L = p.length();
  if (p.closed) {
    s = std::fmod(s, L);
    if (s < 0) s += L;
  }
  return std::clamp(s, 0.0, L);
}
}  // namespace

Eigen::Vector2d Path::point(double s) const {
  s = wrap_s(*this, s);
  const size_t i = std::min(size_t(s / ds), pts.size() - 2);
  const double f = s / ds - double(i);
  return (1 - f) * pts[i] + f * pts[i + 1];
}

double Path::heading_at(double s) const {
  s = wrap_s(*this, s);
  const size_t i = std::min(size_t(s / ds), pts.size() - 2);
  const double f = s / ds - double(i);
  double d = heading[i + 1] - heading[i];
  d = std::remainder(d, 2 * M_PI);
  return heading[i] + f * d;
}

Eigen::Vector2d Path::left(double s) const {
  const double h = heading_at(s);
  return {-std::sin(h), std::cos(h)};
}

Eigen::Vector2d Path::nearest(const Eigen::Vector2d& q) const {
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector2d arg = pts.front();
  for (size_t i = 0; i + 4 < pts.size(); i += 4) {
    const Eigen::Vector2d a = pts[i], b = pts[i + 4], ab = b - a;
    const double t = std::clamp((q - a).dot(ab) / std::max(ab.squaredNorm(), 1e-12), 0.0, 1.0);
    const Eigen::Vector2d c = a + t * ab;
    if ((c - q).norm() < best) { best = (c - q).norm(); arg = c; }
  }
  return arg;
}

void StreetWorld::place_movers(double t_s) {
  scene.dynamic.clear();
  for (const auto& m : movers) {
    const double s = m.s0 + m.speed * t_s;
    if (!path.closed && (s < 0 || s > path.length())) continue;
    const Eigen::Vector2d c = path.point(s) + path.left(s) * m.lateral;
    const float yaw = float(path.heading_at(s));
    const Eigen::Vector2d fwd(std::cos(yaw), std::sin(yaw));
    scene.dynamic.push_back(Primitive::make_box(V3(float(c.x()), float(c.y()), 0.7f),
                                                V3(float(m.length / 2), float(m.width / 2), 0.45f),
                                                yaw, Material::car_paint, float(m.reflectance)));
    const Eigen::Vector2d cc = c - 0.25 * fwd * (m.speed >= 0 ? 1.0 : -1.0);
    scene.dynamic.push_back(Primitive::make_box(V3(float(cc.x()), float(cc.y()), 1.45f),
                                                V3(float(m.length * 0.27), float(m.width / 2 - 0.1), 0.3f),
                                                yaw, Material::car_glass, 0.12f));
  }
  for (const auto& p : walkers) {
    const double s = p.s0 + p.speed * t_s;
    if (!path.closed && (s < 0 || s > path.length())) continue;
    const Eigen::Vector2d c = path.point(s) + path.left(s) * p.lateral;
    scene.dynamic.push_back(Primitive::make_cylinder(float(c.x()), float(c.y()), 0.f, float(p.height),
                                                     float(p.radius), Material::plastic, float(p.reflectance)));
  }
}

std::vector<Pose> drive(const StreetWorld& w, const DriveConfig& cfg, const std::vector<double>& times_s) {
  Rng rng(cfg.seed, 5);
  double t_end = 0;
  for (double t : times_s) t_end = std::max(t_end, t);
  const double key_dt = 3.0;
  std::vector<double> keys;
  for (double t = 0; t <= t_end + 2 * key_dt; t += key_dt) keys.push_back(cfg.v_min + (cfg.v_max - cfg.v_min) * rng.uniform_double());
  const double ph1 = 2 * M_PI * rng.uniform_double(), ph2 = 2 * M_PI * rng.uniform_double();
  auto speed = [&](double t) {  // cosine blend between keypoints
    const size_t k = size_t(t / key_dt);
    const double f = (t - double(k) * key_dt) / key_dt, b = 0.5 - 0.5 * std::cos(M_PI * f);
    return (1 - b) * keys[k] + b * keys[k + 1];
  };
  std::vector<Pose> out;
  for (double t_req : times_s) {
    // Integrate s(t) from 0 with a fixed step (midpoint rule): exact for any time order.
    // The ego drives at `speed` on its lane: the centreline advances by v / (1 − κ·lateral).
    auto ds_dt = [&](double s, double t) {
      const double kappa = std::remainder(w.path.heading_at(s + 0.25) - w.path.heading_at(s - 0.25), 2 * M_PI) / 0.5;
      return speed(t) / std::max(0.2, 1.0 - kappa * w.ego_lateral);
    };
    const double dt = 0.005;
    double s = w.ego_start_s, t = 0;
    while (t + dt <= t_req) { s += dt * ds_dt(s, t + 0.5 * dt); t += dt; }
    s += (t_req - t) * ds_dt(s, 0.5 * (t + t_req));
    const double accel = (speed(t_req + 0.05) - speed(std::max(0.0, t_req - 0.05))) / 0.1;
    const Eigen::Vector2d p = w.path.point(s) + w.path.left(s) * w.ego_lateral;
    const double yaw = w.path.heading_at(s);
    const double pitch = -0.004 * accel + 0.002 * std::sin(0.7 * t_req + ph1);
    const double roll = 0.002 * std::sin(1.3 * t_req + ph2);
    Pose T = Pose::Identity();
    T.linear() = (Eigen::AngleAxisd(yaw, Vec3::UnitZ()) * Eigen::AngleAxisd(pitch, Vec3::UnitY()) *
                  Eigen::AngleAxisd(roll, Vec3::UnitX())).toRotationMatrix();
    T.translation() = Vec3(p.x(), p.y(), cfg.sensor_height_m);
    out.push_back(T);
  }
  return out;
}

}  // namespace sgnlf::sim
