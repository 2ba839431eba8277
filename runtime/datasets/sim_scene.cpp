#include "datasets/sim_scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/rng.hpp"

namespace sgnlf::sim {

Primitive Primitive::make_box(V3 c, V3 half, float yaw, Material m, float refl) {
  Primitive p;
  p.type = box;
  p.center = c;
  p.half = half;
  p.cos_yaw = std::cos(yaw);
  p.sin_yaw = std::sin(yaw);
  p.material = m;
  p.reflectance = refl;
  return p;
}

Primitive Primitive::make_cylinder(float x, float y, float z0, float z1, float r, Material m, float refl) {
  Primitive p;
  p.type = cylinder;
  p.center = V3(x, y, 0.5f * (z0 + z1));
  p.half = V3(r, r, 0.5f * (z1 - z0));
  p.material = m;
  p.reflectance = refl;
  return p;
}

Primitive Primitive::make_ellipsoid(V3 c, V3 radii, Material m, float refl) {
  Primitive p;
  p.type = ellipsoid;
  p.center = c;
  p.half = radii;
  p.material = m;
  p.reflectance = refl;
  return p;
}

void Primitive::bounds(float& x0, float& y0, float& x1, float& y1) const {
  float ex = half.x(), ey = half.y();
  if (type == box) {
    ex = std::abs(cos_yaw) * half.x() + std::abs(sin_yaw) * half.y();
    ey = std::abs(sin_yaw) * half.x() + std::abs(cos_yaw) * half.y();
  }
  x0 = center.x() - ex;
  x1 = center.x() + ex;
  y0 = center.y() - ey;
  y1 = center.y() + ey;
}

namespace {

bool hit_box(const Primitive& p, const V3& o, const V3& d, float t_min, Hit& h) {
  // Into the box frame: rotate by −yaw about z.
  const V3 q = o - p.center;
  const V3 lo(p.cos_yaw * q.x() + p.sin_yaw * q.y(), -p.sin_yaw * q.x() + p.cos_yaw * q.y(), q.z());
  const V3 ld(p.cos_yaw * d.x() + p.sin_yaw * d.y(), -p.sin_yaw * d.x() + p.cos_yaw * d.y(), d.z());
  float t0 = -std::numeric_limits<float>::infinity(), t1 = std::numeric_limits<float>::infinity();
  int axis = -1;
  float sign = 0.f;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(ld[a]) < 1e-12f) {
      if (std::abs(lo[a]) > p.half[a]) return false;
      continue;
    }
    const float inv = 1.f / ld[a];
    float ta = (-p.half[a] - lo[a]) * inv, tb = (p.half[a] - lo[a]) * inv;
    const float s = ld[a] > 0 ? -1.f : 1.f;  // outward normal of the entry face
    if (ta > tb) std::swap(ta, tb);
    if (ta > t0) { t0 = ta; axis = a; sign = s; }
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  if (axis < 0 || !(t0 > t_min) || !(t0 < h.t)) return false;
  V3 nl = V3::Zero();
  nl[axis] = sign;
  h.t = t0;
  h.normal = V3(p.cos_yaw * nl.x() - p.sin_yaw * nl.y(), p.sin_yaw * nl.x() + p.cos_yaw * nl.y(), nl.z());
  return true;
}

bool hit_cylinder(const Primitive& p, const V3& o, const V3& d, float t_min, Hit& h) {
  const float r = p.half.x(), z0 = p.center.z() - p.half.z(), z1 = p.center.z() + p.half.z();
  const float ox = o.x() - p.center.x(), oy = o.y() - p.center.y();
  bool found = false;
  const float a = d.x() * d.x() + d.y() * d.y();
  if (a > 1e-12f) {
    const float b = ox * d.x() + oy * d.y(), c = ox * ox + oy * oy - r * r;
    const float disc = b * b - a * c;
    if (disc >= 0.f && c > 0.f) {
      const float t = (-b - std::sqrt(disc)) / a;
      const float z = o.z() + t * d.z();
      if (t > t_min && t < h.t && z >= z0 && z <= z1) {
        h.t = t;
        h.normal = V3((ox + t * d.x()) / r, (oy + t * d.y()) / r, 0.f);
        found = true;
      }
    }
  }
  if (d.z() < 0.f && o.z() > z1) {  // top cap
    const float t = (z1 - o.z()) / d.z();
    const float x = ox + t * d.x(), y = oy + t * d.y();
    if (t > t_min && t < h.t && x * x + y * y <= r * r) {
      h.t = t;
      h.normal = V3::UnitZ();
      found = true;
    }
  }
  return found;
}

bool hit_ellipsoid(const Primitive& p, const V3& o, const V3& d, float t_min, Hit& h) {
  const V3 q = (o - p.center).cwiseQuotient(p.half), e = d.cwiseQuotient(p.half);
  const float a = e.squaredNorm(), b = q.dot(e), c = q.squaredNorm() - 1.f;
  const float disc = b * b - a * c;
  if (disc < 0.f || c <= 0.f) return false;
  const float t = (-b - std::sqrt(disc)) / a;
  if (!(t > t_min && t < h.t)) return false;
  h.t = t;
  h.normal = (q + t * e).cwiseQuotient(p.half).normalized();
  return true;
}

}  // namespace

bool intersect(const Primitive& p, const V3& o, const V3& d, float t_min, Hit& h) {
  bool ok = false;
  switch (p.type) {
    case Primitive::box: ok = hit_box(p, o, d, t_min, h); break;
    case Primitive::cylinder: ok = hit_cylinder(p, o, d, t_min, h); break;
    case Primitive::ellipsoid: ok = hit_ellipsoid(p, o, d, t_min, h); break;
  }
  if (ok) {
    h.reflectance = p.reflectance;
    h.material = p.material;
    h.label = p.label;
    if (p.windows && std::abs(h.normal.z()) < 0.5f) {
      // Facade windows: 1.4 × 1.4 m panes on a 3 m × 3.2 m grid above the ground floor.
      const V3 q = o + h.t * d - p.center;
      const float along = std::abs(-p.sin_yaw * h.normal.x() + p.cos_yaw * h.normal.y()) > 0.5f
                              ? p.cos_yaw * q.x() + p.sin_yaw * q.y()     // face normal along local y
                              : -p.sin_yaw * q.x() + p.cos_yaw * q.y();  // face normal along local x
      const float z = q.z() + p.half.z();
      const float fu = std::fmod(along + 1000.f, 3.0f), fz = std::fmod(z, 3.2f);
      if (z > 3.0f && fu > 0.8f && fu < 2.2f && fz > 0.9f && fz < 2.3f) {
        h.material = Material::glass;
        h.reflectance = 0.1f;
      }
    }
  }
  return ok;
}

void Scene::build(float cell_m) {
  require(cell_m > 0.f, "Scene::build: cell size must be positive");
  cell_ = cell_m;
  float X0 = 0, Y0 = 0, X1 = 1, Y1 = 1;
  if (!prims_.empty()) {
    X0 = Y0 = std::numeric_limits<float>::infinity();
    X1 = Y1 = -X0;
    for (const auto& p : prims_) {
      float a, b, c, e;
      p.bounds(a, b, c, e);
      X0 = std::min(X0, a); Y0 = std::min(Y0, b); X1 = std::max(X1, c); Y1 = std::max(Y1, e);
    }
  }
  x0_ = X0 - cell_;
  y0_ = Y0 - cell_;
  nx_ = int(std::ceil((X1 - x0_) / cell_)) + 1;
  ny_ = int(std::ceil((Y1 - y0_) / cell_)) + 1;
  require(double(nx_) * ny_ < 5e7, "Scene::build: grid too large");
  std::vector<std::vector<uint32_t>> cells(size_t(nx_) * ny_);
  cell_top_.assign(cells.size(), -std::numeric_limits<float>::infinity());
  for (uint32_t i = 0; i < prims_.size(); ++i) {
    float a, b, c, e;
    prims_[i].bounds(a, b, c, e);
    const int i0 = int((a - x0_) / cell_), i1 = int((c - x0_) / cell_);
    const int j0 = int((b - y0_) / cell_), j1 = int((e - y0_) / cell_);
    for (int j = j0; j <= j1; ++j)
      for (int k = i0; k <= i1; ++k) {
        cells[size_t(j) * nx_ + k].push_back(i);
        cell_top_[size_t(j) * nx_ + k] = std::max(cell_top_[size_t(j) * nx_ + k], prims_[i].top());
      }
  }
  cell_start_.assign(cells.size() + 1, 0);
  cell_items_.clear();
  for (size_t c = 0; c < cells.size(); ++c) {
    cell_start_[c] = uint32_t(cell_items_.size());
    cell_items_.insert(cell_items_.end(), cells[c].begin(), cells[c].end());
  }
  cell_start_[cells.size()] = uint32_t(cell_items_.size());
  built_ = true;
}

bool Scene::cast_static(const V3& o, const V3& d, float t_max, Hit& h) const {
  // 2-D DDA (Amanatides & Woo) over the x–y grid, clipped to the grid rectangle.
  const float gx1 = x0_ + nx_ * cell_, gy1 = y0_ + ny_ * cell_;
  float t_enter = 0.f, t_exit = t_max;
  const float dd[2] = {d.x(), d.y()}, oo[2] = {o.x(), o.y()}, lo[2] = {x0_, y0_}, hi[2] = {gx1, gy1};
  for (int a = 0; a < 2; ++a) {
    if (std::abs(dd[a]) < 1e-12f) {
      if (oo[a] < lo[a] || oo[a] >= hi[a]) return false;
      continue;
    }
    float ta = (lo[a] - oo[a]) / dd[a], tb = (hi[a] - oo[a]) / dd[a];
    if (ta > tb) std::swap(ta, tb);
    t_enter = std::max(t_enter, ta);
    t_exit = std::min(t_exit, tb);
  }
  if (t_enter >= t_exit) return false;
  const float px = o.x() + t_enter * d.x(), py = o.y() + t_enter * d.y();
  int ix = std::clamp(int((px - x0_) / cell_), 0, nx_ - 1);
  int iy = std::clamp(int((py - y0_) / cell_), 0, ny_ - 1);
  const int sx = d.x() > 0 ? 1 : -1, sy = d.y() > 0 ? 1 : -1;
  const float inf = std::numeric_limits<float>::infinity();
  const float dtx = std::abs(d.x()) > 1e-12f ? cell_ / std::abs(d.x()) : inf;
  const float dty = std::abs(d.y()) > 1e-12f ? cell_ / std::abs(d.y()) : inf;
  float tx = std::abs(d.x()) > 1e-12f ? (x0_ + (ix + (sx > 0)) * cell_ - o.x()) / d.x() : inf;
  float ty = std::abs(d.y()) > 1e-12f ? (y0_ + (iy + (sy > 0)) * cell_ - o.y()) / d.y() : inf;
  h.t = t_max;
  bool found = false;
  float t_cell = t_enter;
  while (true) {
    const float t_next = std::min(tx, ty);
    const size_t c = size_t(iy) * nx_ + ix;
    // Skip cells whose contents lie entirely below the ray inside the cell (ray rising above).
    const float z_min_in_cell = o.z() + std::min(t_cell * d.z(), std::min(t_next, t_max) * d.z());
    if (z_min_in_cell <= cell_top_[c])
      for (uint32_t k = cell_start_[c]; k < cell_start_[c + 1]; ++k)
        found |= intersect(prims_[cell_items_[k]], o, d, 1e-4f, h);
    if (found && h.t <= t_next) return true;
    if (t_next >= t_exit) break;
    if (tx < ty) { ix += sx; tx += dtx; if (ix < 0 || ix >= nx_) break; }
    else         { iy += sy; ty += dty; if (iy < 0 || iy >= ny_) break; }
    t_cell = t_next;
  }
  return found;
}

bool Scene::cast(const V3& o, const V3& d, float t_max, Hit& h) const {
  require(built_, "Scene::cast: build() was not called after adding primitives");
  h.t = t_max;
  bool found = cast_static(o, d, t_max, h);
  if (!found) h.t = t_max;
  for (const auto& p : dynamic) found |= intersect(p, o, d, 1e-4f, h);
  if (d.z() < 0.f && o.z() > ground_z) {
    const float t = (ground_z - o.z()) / d.z();
    if (t > 0.f && t < h.t) {
      h.t = t;
      h.normal = V3::UnitZ();
      h.material = Material::asphalt;
      h.label = 0;
      // Patchy asphalt: value noise on a 0.5 m lattice from Philox (deterministic).
      const float x = o.x() + t * d.x(), y = o.y() + t * d.y();
      const auto blk = philox_block(texture_seed, 77u,
                                    (uint64_t(uint32_t(int32_t(std::floor(x * 2.f)))) << 32) |
                                        uint32_t(int32_t(std::floor(y * 2.f))));
      h.reflectance = ground_reflectance * (1.f + ground_texture * (2.f * u32_to_unit_float(blk[0]) - 1.f));
      found = true;
    }
  }
  return found;
}

}  // namespace sgnlf::sim
