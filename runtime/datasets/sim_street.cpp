// Procedural street generation (see sim_street.hpp). All draws come from Rng(seed, stream) in a
// fixed order, so a seed gives one world bit for bit, whatever the compiler (core/rng.hpp: never
// two draws in one argument list; tests/datasets/test_simulate_compiler.cpp). Draws that were
// once in an argument list are made last argument first, the order GCC used, so the data of
// every committed result is unchanged.
#include "datasets/sim_street.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/rng.hpp"

namespace sgnlf::sim {
namespace {

using V2 = Eigen::Vector2d;

void append(Path& p, double len, double curvature) {
  const int n = std::max(1, int(std::lround(len / p.ds)));
  curvature *= len / (n * p.ds);  // keep the piece's total turn exact despite the rounding
  for (int i = 0; i < n; ++i) {
    const double h = p.heading.back();
    const double hm = h + 0.5 * curvature * p.ds;
    p.pts.push_back(p.pts.back() + p.ds * V2(std::cos(hm), std::sin(hm)));
    p.heading.push_back(h + curvature * p.ds);
  }
}

Path make_open_path(Rng& rng, double needed) {
  Path p;
  p.pts = {V2(0, 0)};
  p.heading = {0.0};
  append(p, 90.0 + rng.uniform(5.f, 25.f), 0.0);  // the first turn falls inside the drive
  bool turn = true;
  while (p.length() < needed) {
    if (turn) {
      const double r = rng.uniform(18.f, 45.f), ang = rng.uniform(0.45f, 1.4f);
      append(p, r * ang, (rng.uniform() < 0.5f ? 1.0 : -1.0) / r);
    } else {
      append(p, rng.uniform(25.f, 70.f), 0.0);
    }
    turn = !turn;
  }
  return p;
}

// One straight road (the dynamic twins: actors on arcs of gentle curvature stay in their lanes).
Path make_straight_path(double needed) {
  Path p;
  p.pts = {V2(0, 0)};
  p.heading = {0.0};
  append(p, needed, 0.0);
  return p;
}

Path make_loop_path(double L, double W, double R) {
  Path p;
  p.closed = true;
  p.pts = {V2(0, 0)};
  p.heading = {0.0};
  const double k = -1.0 / R, arc = 0.5 * M_PI * R;  // clockwise: the ego's lane is the inner one
  append(p, L / 2 - R, 0);
  append(p, arc, k);
  append(p, W - 2 * R, 0);
  append(p, arc, k);
  append(p, L - 2 * R, 0);
  append(p, arc, k);
  append(p, W - 2 * R, 0);
  append(p, arc, k);
  append(p, L / 2 - R, 0);
  // Close exactly: spread the small rounding gap linearly along the loop.
  const V2 gap = p.pts.back() - p.pts.front();
  for (size_t i = 0; i < p.pts.size(); ++i) p.pts[i] -= gap * (double(i) / double(p.pts.size() - 1));
  return p;
}

struct Placer {
  StreetWorld& w;
  Rng& rng;
  // A box at arc position s, lateral offset `lat` (signed, + = left), oriented with the road.
  Primitive box_at(double s, double lat, double along, V3 half, float z_center, Material m, float refl,
                   float yaw_jitter = 0.f) {
    const V2 c = w.path.point(s) + w.path.left(s) * lat;
    const double h = w.path.heading_at(s);
    const V2 c2 = c + along * V2(std::cos(h), std::sin(h));
    return Primitive::make_box(V3(float(c2.x()), float(c2.y()), z_center), half, float(h) + yaw_jitter, m, refl);
  }
  // Smallest distance from the primitive's footprint to the centreline (box: its outline
  // sampled every ≤ 2 m; round shapes: centre distance minus radius).
  double clearance(const Primitive& p) const {
    const V2 c(p.center.x(), p.center.y());
    if (p.type != Primitive::box) return w.path.distance(c) - std::max(p.half.x(), p.half.y());
    double d = std::numeric_limits<double>::infinity();
    const int nx = 1 + int(p.half.x()), ny = 1 + int(p.half.y());
    for (int i = -nx; i <= nx; ++i)
      for (int j = -ny; j <= ny; ++j) {
        if (std::abs(i) != nx && std::abs(j) != ny) continue;  // outline only
        const double lx = p.half.x() * i / nx, ly = p.half.y() * j / ny;
        const V2 q = c + V2(p.cos_yaw * lx - p.sin_yaw * ly, p.sin_yaw * lx + p.cos_yaw * ly);
        d = std::min(d, w.path.distance(q));
      }
    return d;
  }
  // Adds a primitive whose footprint stays at least `clear` from the road centreline. With
  // `push_m` > 0 an object too close (inner side of a bend) is moved outward, up to push_m.
  bool add_clear(Primitive p, double clear, double push_m = 0.0) {
    double moved = 0;
    for (int it = 0; it < 6; ++it) {
      const double d = clearance(p);
      if (d >= clear) { w.scene.add(p); return true; }
      const double step = clear - d + 0.1;
      if (moved + step > push_m) return false;
      const V2 c(p.center.x(), p.center.y());
      const V2 dir = (c - w.path.nearest(c)).normalized();
      p.center.x() += float(step * dir.x());
      p.center.y() += float(step * dir.y());
      moved += step;
    }
    return false;
  }
};

Material pick_facade(Rng& rng, float& refl) {
  const float u = rng.uniform();
  if (u < 0.3f) { refl = rng.uniform(0.22f, 0.34f); return Material::brick; }
  if (u < 0.6f) { refl = rng.uniform(0.38f, 0.55f); return Material::plaster; }
  if (u < 0.82f) { refl = rng.uniform(0.28f, 0.40f); return Material::concrete; }
  if (u < 0.92f) { refl = rng.uniform(0.07f, 0.14f); return Material::glass; }
  refl = rng.uniform(0.25f, 0.35f);
  return Material::stone;
}

void add_side(Placer& P, int side, double L, double wr, double sw) {
  Rng& rng = P.rng;
  const double sgn = double(side);
  // Sidewalk with curb (0.15 m), 4 m segments.
  for (double s = 0; s < L; s += 4.0)
    P.add_clear(P.box_at(s + 2.0, sgn * (wr + sw / 2), 0, V3(2.05f, float(sw / 2), 0.075f), 0.075f,
                         Material::concrete, rng.uniform(0.26f, 0.34f)), wr - 0.1, 0.6);
  // Edge line of the driving lanes and parked cars in the parking strip.
  for (double s = 0; s < L; s += 4.0)
    P.add_clear(P.box_at(s + 2.0, sgn * (wr - 2.2), 0, V3(1.95f, 0.08f, 0.01f), 0.01f, Material::paint, 0.75f), wr - 2.4);
  for (double s = rng.uniform(0.f, 6.f); s < L; s += rng.uniform(5.2f, 9.f)) {
    if (rng.uniform() < 0.45f) continue;
    const float len = rng.uniform(3.9f, 4.9f), refl = rng.uniform(0.15f, 0.7f), jit = rng.uniform(-0.05f, 0.05f);
    P.add_clear(P.box_at(s, sgn * (wr - 1.2), 0, V3(len / 2, 0.88f, 0.42f), 0.67f, Material::car_paint, refl, jit), wr - 2.3, 0.0);
    P.add_clear(P.box_at(s, sgn * (wr - 1.2), -0.2, V3(len * 0.26f, 0.78f, 0.28f), 1.37f, Material::car_glass, 0.12f, jit), wr - 2.3);
  }
  // Poles (street lamps, signs) at the curb.
  for (double s = rng.uniform(0.f, 20.f); s < L; s += rng.uniform(16.f, 34.f)) {
    const V2 c = P.w.path.point(s) + P.w.path.left(s) * (sgn * (wr + 0.45));
    const bool sign = rng.uniform() < 0.35f;
    const float h = sign ? rng.uniform(2.4f, 3.0f) : rng.uniform(6.f, 8.5f);
    const float pole_refl = rng.uniform(0.35f, 0.55f), pole_r = rng.uniform(0.06f, 0.13f);
    if (!P.add_clear(Primitive::make_cylinder(float(c.x()), float(c.y()), 0.f, h, pole_r, Material::metal, pole_refl), wr + 0.2)) continue;
    if (sign) P.w.scene.add(P.box_at(s, sgn * (wr + 0.45), 0, V3(0.03f, 0.35f, 0.35f), h - 0.2f, Material::paint, 0.95f));
    else P.w.scene.add(P.box_at(s, sgn * (wr - 0.3), 0, V3(0.15f, 0.75f, 0.06f), h, Material::metal, 0.5f));
  }
  // Trees along the sidewalk (most streets).
  if (rng.uniform() < 0.7f)
    for (double s = rng.uniform(0.f, 10.f); s < L; s += rng.uniform(8.f, 15.f)) {
      const V2 c = P.w.path.point(s) + P.w.path.left(s) * (sgn * (wr + sw - 0.9));
      const float th = rng.uniform(2.0f, 3.2f), rx = rng.uniform(1.4f, 2.6f), rz = rng.uniform(1.5f, 3.0f);
      const float bark_refl = rng.uniform(0.18f, 0.3f), trunk_r = rng.uniform(0.12f, 0.25f);
      if (!P.add_clear(Primitive::make_cylinder(float(c.x()), float(c.y()), 0.f, th + 0.5f, trunk_r, Material::bark, bark_refl), wr + 0.2)) continue;
      const float leaf_refl = rng.uniform(0.2f, 0.36f), ry = rx * rng.uniform(0.85f, 1.15f);
      P.w.scene.add(Primitive::make_ellipsoid(V3(float(c.x()), float(c.y()), th + 0.8f * rz), V3(rx, ry, rz), Material::foliage, leaf_refl));
    }
  // Clutter on the sidewalk: bins, bollards, boxes.
  for (double s = rng.uniform(0.f, 8.f); s < L; s += rng.uniform(4.f, 16.f)) {
    const double lat = sgn * (wr + rng.uniform(0.5f, float(sw) - 0.4f));
    const V2 c = P.w.path.point(s) + P.w.path.left(s) * lat;
    const float u = rng.uniform();
    const float refl = rng.uniform(0.1f, 0.6f);
    if (u < 0.4f) {
      const float r = rng.uniform(0.08f, 0.35f), z1 = rng.uniform(0.8f, 1.1f);
      P.add_clear(Primitive::make_cylinder(float(c.x()), float(c.y()), 0.f, z1, r, Material::plastic, refl), wr + 0.1);
    } else {
      const float hz = rng.uniform(0.3f, 0.8f), hy = rng.uniform(0.2f, 0.6f), hx = rng.uniform(0.2f, 0.7f);
      P.add_clear(P.box_at(s, lat, 0, V3(hx, hy, hz), 0.f, Material::plastic, refl), wr + 0.1);
    }
  }
  // Buildings: frontage runs with gaps (walls in some), varied setback, depth, height, material.
  double setback = rng.uniform(0.3f, 5.f) + P.w.extra_setback_m;
  for (double s = rng.uniform(-10.f, 0.f); s < L + 10;) {
    const double front = rng.uniform(8.f, 26.f);
    if (rng.uniform() < 0.25f) setback = rng.uniform(0.3f, 6.f) + P.w.extra_setback_m;
    const double depth = rng.uniform(8.f, 16.f), height = rng.uniform() < 0.3f ? rng.uniform(3.f, 7.f) : rng.uniform(7.f, 24.f);
    float refl;
    const Material m = pick_facade(rng, refl);
    const double lat = sgn * (wr + sw + setback + depth / 2);
    const double sc = s + front / 2;
    Primitive b = P.box_at(sc, lat, 0, V3(float(front / 2), float(depth / 2), float(height / 2)), float(height / 2), m, refl);
    b.windows = m != Material::glass && rng.uniform() < 0.6f;
    if (P.add_clear(b, wr + sw - 0.2, 12.0)) {
      const Primitive B = P.w.scene.primitives().back();  // as placed (maybe pushed outward)
      auto attach = [&](double ax, double ay, V3 half, float z, Material mm, float rr) {
        const V3 c(B.center.x() + float(B.cos_yaw * ax - B.sin_yaw * ay),
                   B.center.y() + float(B.sin_yaw * ax + B.cos_yaw * ay), z);
        P.w.scene.add(Primitive::make_box(c, half, std::atan2(B.sin_yaw, B.cos_yaw), mm, rr));
      };
      if (rng.uniform() < 0.35f)  // rooftop structure
        attach(0, sgn * 1.0, V3(float(front / 4), float(depth / 4), 1.5f), float(height + 1.5), Material::concrete, refl);
      if (rng.uniform() < 0.4f && height > 8)  // balconies / bays protruding from the road-side facade
        for (double z = 4.0; z < height - 2; z += 3.0)
          for (double a = -front / 2 + 2; a < front / 2 - 2; a += rng.uniform(4.f, 7.f))
            attach(a, -sgn * (depth / 2 + 0.45), V3(1.2f, 0.45f, 0.12f), float(z), Material::concrete, 0.35f);
    }
    const float ug = rng.uniform();  // attached, a gap, or a cross street
    double gap = ug < 0.5f ? rng.uniform(0.f, 1.f) : ug < 0.82f ? rng.uniform(2.f, 12.f) : rng.uniform(14.f, 28.f);
    if (gap > 2.f && gap < 13.f && rng.uniform() < 0.6f) {  // wall or fence closing the gap
      const float wall_refl = rng.uniform(0.2f, 0.4f), wall_z = rng.uniform(0.6f, 1.2f);
      P.add_clear(P.box_at(s + front + gap / 2, sgn * (wr + sw + setback + 0.15), 0, V3(float(gap / 2), 0.15f, 0.9f), wall_z, Material::stone, wall_refl), wr + sw - 0.2, 3.0);
    }
    s += front + gap;
  }
}

}  // namespace

StreetWorld generate_street(const StreetConfig& cfg) {
  Rng rng(cfg.seed, 1);
  StreetWorld w;
  w.road_half_width = rng.uniform(5.2f, 7.0f);
  w.sidewalk_width = rng.uniform(2.2f, 4.5f);
  if (cfg.layout == "loop") {
    const double loop_w = rng.uniform(18.f, 22.f) + 4 * w.road_half_width;
    const double loop_l = rng.uniform(24.f, 28.f) + 4 * w.road_half_width;
    w.path = make_loop_path(loop_l, loop_w, 10.0);
    w.ego_start_s = 0;
  } else if (cfg.layout == "straight") {
    w.path = make_straight_path(cfg.drive_length_m + 180.0);
    w.ego_start_s = 90.0;
  } else {
    w.path = make_open_path(rng, cfg.drive_length_m + 180.0);
    w.ego_start_s = 90.0;
  }
  const double wr = w.road_half_width, sw = w.sidewalk_width, L = w.path.length();
  w.ego_lateral = -(wr - 2.2) / 2;
  w.extra_setback_m = cfg.extra_setback_m;
  w.scene.texture_seed = cfg.seed;
  w.scene.ground_reflectance = rng.uniform(0.22f, 0.32f);
  Placer P{w, rng};
  for (double s = 0; s < L; s += 9.0)  // dashed centre line
    P.add_clear(P.box_at(s + 1.5, 0, 0, V3(1.5f, 0.08f, 0.01f), 0.01f, Material::paint, 0.7f), 0.0);
  add_side(P, +1, L, wr, sw);
  add_side(P, -1, L, wr, sw);
  Rng mrng(cfg.seed, 2);
  for (int i = 0; i < cfg.moving_vehicles; ++i) {
    MovingVehicle m;
    const bool oncoming = i % 2 == 0;
    m.speed = oncoming ? -mrng.uniform(6.f, 11.f) : mrng.uniform(12.f, 15.f);
    m.s0 = w.ego_start_s + (oncoming ? mrng.uniform(30.f, 120.f) : mrng.uniform(12.f, 30.f) + 10.0 * i);
    m.lateral = oncoming ? (wr - 2.2) / 2 : w.ego_lateral;
    m.length = mrng.uniform(4.f, 5.f);
    m.reflectance = mrng.uniform(0.15f, 0.7f);
    w.movers.push_back(m);
  }
  if (cfg.vegetation) add_vegetation(w, cfg.seed);
  if (cfg.pedestrians > 0) add_pedestrians(w, cfg.pedestrians, cfg.seed);
  w.scene.build(2.0f);
  return w;
}

}  // namespace sgnlf::sim
