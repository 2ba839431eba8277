// Cross-frame reprojection, forward: the pixel rule against the protocol's rounding, the device
// against the float host mirror (pixels, mask and winners bit for bit, D_ij = sqrt(q) within
// sqrt's ulp bound) and against project_points() (protocol §1) on simulated frames, an identity
// relative pose, a wall seen after a known translation, the z-buffer (nearest wins, equal ranges
// go to the smallest source index), the range limits and run-to-run determinism.
#include <catch2/catch.hpp>

#include <cstring>

#include "core/rng.hpp"
#include "reproject_reference.hpp"
#include "reproject_test_data.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

namespace {
// The protocol's pixel of a point (project_points' formula, double).
std::pair<long, long> protocol_pixel(const Sensor& s, double x, double y, double z) {
  const double fov_down = s.fov_deg - s.fov_up_deg;
  const long c = std::lround((M_PI - std::atan2(y, x)) / (2.0 * M_PI / s.width));
  const long r = std::lround(s.height - (std::atan2(z, std::sqrt(x * x + y * y)) +
                                         fov_down * M_PI / 180.0) /
                                            (s.fov_deg * M_PI / 180.0 / s.height));
  return {r, c};
}

uint32_t bits(float v) {
  uint32_t b;
  std::memcpy(&b, &v, 4);
  return b;
}

// Pixels whose mask or winner differs between the device images and the float mirror. Exact
// by construction on every device (reproject.cl: the pixel, the z-buffer's keys and so the mask
// and winners use only IEEE multiplications, additions and comparisons, contraction off).
size_t mismatches(const render::ReprojectionImages& dev, const test::RefReprojection<float>& ref) {
  size_t bad = 0;
  for (size_t t = 0; t < ref.range.size(); ++t)
    bad += dev.mask[t] != ref.mask[t] || dev.winner[t] != ref.winner[t];
  return bad;
}

// D_ij = sqrt(q) of the same q bits: bit-equal where sqrt is correctly rounded (PoCL on x86),
// within OpenCL's 3 ulp for sqrt elsewhere (3 · 2^-23 < 4e-7 relative); a wrong winner or range
// is off by far more. Empty pixels are 0 on both sides.
constexpr double kSqrtUlps = 4e-7;

size_t count(const std::vector<float>& mask) {
  size_t n = 0;
  for (float m : mask) n += m > 0.5f;
  return n;
}
}  // namespace

TEST_CASE("Pixel-boundary tests give the protocol's pixel from any first guess", "[render][reproject]") {
  for (const Sensor& s : {sensor_preset("kitti360"), sensor_preset("nuscenes")}) {
    const auto gd = test::ref_reproj_geometry<double>(s, s, 1.0);
    const auto gf = test::ref_reproj_geometry<float>(s, s, 1.0);
    Rng rng(7, 1);
    int inside = 0, float_differs = 0;
    const int n = 20000;
    for (int k = 0; k < n; ++k) {
      // Directions over the full azimuth and a band a little wider than the field of view.
      const double beta = rng.uniform_double() * 2 * M_PI - M_PI;
      const double alpha = (s.fov_up_deg + 3 - rng.uniform_double() * (s.fov_deg + 6)) * M_PI / 180;
      const double range = 1 + 60 * rng.uniform_double();
      const double x = range * std::cos(alpha) * std::cos(beta),
                   y = range * std::cos(alpha) * std::sin(beta), z = range * std::sin(alpha);
      const auto [pr, pc] = protocol_pixel(s, x, y, z);
      const int r = test::ref_row(gd, z, x * x + y * y), c = test::ref_column(gd.col, s.width, x, y);
      INFO(s.name << " point " << x << " " << y << " " << z);
      REQUIRE(r == std::clamp<long>(pr, -1, s.height));
      REQUIRE(c == pc);
      inside += r >= 0 && r < s.height;
      const float xf = float(x), yf = float(y), zf = float(z), qf = xf * xf + yf * yf;
      const int rf = test::ref_row(gf, zf, qf), cf = test::ref_column(gf.col, s.width, xf, yf);
      float_differs += rf != r || cf != c;
      // The walk ends in the same pixel from any first guess within a quarter turn (the
      // kernel guesses differently, to within ~1e-5 rad), and from any row.
      for (int guess : {-5, 0, rf - 3, rf + 3, s.height + 4})
        REQUIRE(test::ref_row_from(gf, zf, qf, guess) == rf);
      for (int guess : {cf - 9, cf + 9, cf - s.width / 4, cf + s.width / 4})
        REQUIRE(test::ref_column_from(gf.col, s.width, xf, yf, guess) == cf);
    }
    CHECK(inside > n / 2);
    CHECK(float_differs < n / 1000);  // float rounding moves only points on a boundary
  }
}

TEST_CASE("Device forward equals the float host mirror on simulated frames",
          "[render][reproject]") {
  auto& rt = test::runtime();
  for (const std::string seq : {"kitti360-low-a", "nuscenes-low-a"}) {
    const Dataset& d = test::reproj_pair(seq);
    const Sensor& s = d.sensor;
    render::CrossFrameReprojection rp(rt, s, s, 1.0);
    const auto g = test::ref_reproj_geometry<float>(s, s, 1.0);
    const Pose Ti = d.frames[0].T_world_lidar, Tj = d.frames[1].T_world_lidar;
    // The true relative pose, and one 0.3 m and 2° off (as a pose-free run sees it).
    for (const Pose& Tj_used : {Tj, Tj * test::make_pose(Vec3(0.01, -0.02, 0.03), Vec3(0.2, -0.1, 0.15))}) {
      const auto dev = test::device_reproject(rp, d.frames[0].image.range, Ti, Tj_used);
      const auto ref = test::ref_reproject_forward(g, d.frames[0].image.range,
                                                   dev.ctx.rows_lidarj_lidari);
      INFO(seq);
      CHECK(mismatches(dev.images, ref) == 0);
      CHECK(test::sym_rel_err(dev.images.range, ref.range) <= kSqrtUlps);
      // Not vacuous: most of frame i's returns land in frame j, and some pixels hold several.
      const size_t valid = count(d.frames[0].image.ray_drop), covered = count(dev.images.mask);
      CHECK(covered > valid / 2);
      CHECK(covered < valid);
    }
  }
  // Frame i at a quarter of the columns (a cheaper render) into frame j's full image.
  const Dataset& narrow = test::reproj_pair("kitti360-low-a", 256);
  const Dataset& full = test::reproj_pair("kitti360-low-a");
  render::CrossFrameReprojection rp(rt, narrow.sensor, full.sensor, 1.0);
  const auto g = test::ref_reproj_geometry<float>(narrow.sensor, full.sensor, 1.0);
  const auto dev = test::device_reproject(rp, narrow.frames[0].image.range,
                                          narrow.frames[0].T_world_lidar, full.frames[1].T_world_lidar);
  const auto ref = test::ref_reproject_forward(g, narrow.frames[0].image.range, dev.ctx.rows_lidarj_lidari);
  CHECK(mismatches(dev.images, ref) == 0);
  CHECK(test::sym_rel_err(dev.images.range, ref.range) <= kSqrtUlps);
  CHECK(count(dev.images.mask) > count(narrow.frames[0].image.ray_drop) / 2);
}

TEST_CASE("Device forward agrees with project_points() of the moved points", "[render][reproject]") {
  auto& rt = test::runtime();
  const Dataset& d = test::reproj_pair("kitti360-low-a");
  const Sensor& s = d.sensor;
  render::CrossFrameReprojection rp(rt, s, s, 1.0);
  const Pose Ti = d.frames[0].T_world_lidar, Tj = d.frames[1].T_world_lidar;
  const auto dev = test::device_reproject(rp, d.frames[0].image.range, Ti, Tj);
  std::vector<PointXYZI> moved;
  const auto dirs = ray_directions(s);
  const auto& depth = d.frames[0].image.range;
  for (size_t p = 0; p < depth.size(); ++p) {
    if (!(depth[p] > 0.f)) continue;
    const Vec3 y = dev.ctx.T_lidarj_lidari *
                   (double(depth[p]) * Vec3(dirs[3 * p], dirs[3 * p + 1], dirs[3 * p + 2]));
    moved.push_back({float(y.x()), float(y.y()), float(y.z()), 0.f});
  }
  const RangeImage proj = project_points(s, moved);
  size_t both = 0, differ = 0, mask_differs = 0;
  for (size_t t = 0; t < proj.size(); ++t) {
    const bool a = proj.range[t] > 0.f, b = dev.images.mask[t] > 0.5f;
    mask_differs += a != b;
    if (a && b) {
      ++both;
      differ += std::abs(proj.range[t] - dev.images.range[t]) > 1e-5f * proj.range[t];
    }
  }
  INFO("both " << both << " range differs " << differ << " mask differs " << mask_differs);
  CHECK(both > proj.size() / 4);
  // Float against double rounding moves points that sit on a pixel boundary: a handful.
  CHECK(mask_differs <= both / 1000);
  CHECK(differ <= both / 1000);
}

TEST_CASE("An identity relative pose reproduces D_i on its own pixels within the range limits",
          "[render][reproject]") {
  auto& rt = test::runtime();
  const Dataset& d = test::reproj_pair("nuscenes-low-a");
  const Sensor& s = d.sensor;  // range limits 1.8 … 80 m
  REQUIRE(s.min_range_m == Approx(1.8));
  std::vector<float> depth = d.frames[0].image.range;
  const int W = s.width;
  depth[size_t(10 * W + 5)] = 85.f;    // beyond the maximum range
  depth[size_t(10 * W + 6)] = 80.01f;  // just beyond the maximum
  depth[size_t(10 * W + 7)] = 1.0f;    // below the minimum
  depth[size_t(10 * W + 8)] = 79.9f;   // kept
  depth[size_t(10 * W + 9)] = 1.9f;    // kept
  depth[size_t(11 * W + 9)] = 0.f;     // a hole
  // The same non-trivial pose for both frames: T_lidarj_lidari is the identity. In metres and
  // in the normalised scene (depths and translations · scale, limits scaled by range_scale).
  for (const double scale : {1.0, 0.0125}) {
    std::vector<float> depth_s = depth;
    for (auto& v : depth_s) v = float(v * scale);
    const Pose T = test::make_pose(Vec3(0.3, -0.2, 1.1), Vec3(12.0, -3.0, 1.5) * scale);
    render::CrossFrameReprojection rp(rt, s, s, scale);
    const auto dev = test::device_reproject(rp, depth_s, T, T);
    size_t kept = 0;
    for (size_t p = 0; p < depth.size(); ++p) {
      const bool expect = depth[p] > 1.8f && depth[p] < 80.f;
      INFO("scale " << scale << " pixel " << p << " depth " << depth[p]);
      REQUIRE((dev.images.mask[p] > 0.5f) == expect);
      if (!expect) {
        REQUIRE(dev.images.winner[p] == -1);
        REQUIRE(dev.images.range[p] == 0.f);
        continue;
      }
      ++kept;
      REQUIRE(dev.images.winner[p] == int(p));
      REQUIRE(dev.images.range[p] == Approx(depth_s[p]).epsilon(1e-6));
    }
    CHECK(kept > depth.size() / 3);
  }
}

TEST_CASE("A known translation towards a planar wall gives the wall's ranges in frame j",
          "[render][reproject]") {
  auto& rt = test::runtime();
  Sensor s;
  s.name = "wall";
  s.height = 32;
  s.width = 512;
  s.fov_up_deg = 10.0;
  s.fov_deg = 40.0;
  // Frame i faces the wall x = 20 m of its own frame; frame j is frame i moved by Δ (same
  // orientation), so the wall is at x = 20 − Δx in frame j.
  const double X0 = 20.0;
  const Vec3 delta(3.0, 1.0, 0.5);
  const Pose T_world_lidar_i = test::make_pose(Vec3(0.1, 0.2, -0.7), Vec3(5, 6, 1));
  const Pose T_world_lidar_j = T_world_lidar_i * test::make_pose(Vec3::Zero(), delta);
  const auto dirs = ray_directions(s);
  std::vector<float> depth(size_t(s.height) * s.width, 0.f);
  for (size_t p = 0; p < depth.size(); ++p)
    if (dirs[3 * p] > 0.3f) depth[p] = float(X0 / dirs[3 * p]);
  render::CrossFrameReprojection rp(rt, s, s, 1.0);
  const auto dev = test::device_reproject(rp, depth, T_world_lidar_i, T_world_lidar_j);
  // A winner sits within half a pixel of the pixel's centre ray in each direction; on a plane
  // at distance h, range h/cos θ changes by r·tan θ per radian away from the normal.
  const double half_diag = std::hypot(M_PI / s.width, 0.5 * s.fov_deg / s.height * M_PI / 180);
  const double h = X0 - delta.x();
  size_t facing = 0, covered = 0;
  for (size_t t = 0; t < depth.size(); ++t) {
    const double vx = dirs[3 * t];
    if (vx < 0.6) continue;  // within 53° of the wall's normal
    ++facing;
    if (dev.images.mask[t] < 0.5f) continue;
    ++covered;
    const double expect = h / vx, tan_t = std::sqrt(1 - vx * vx) / vx;
    INFO("pixel " << t << " D_ij " << dev.images.range[t] << " expected " << expect);
    REQUIRE(std::abs(dev.images.range[t] - expect) <= 1.2 * expect * tan_t * half_diag + 1e-4 * expect);
    // The winner is a wall point: its range in frame j is exact.
    const int w = dev.images.winner[size_t(t)];
    const Vec3 y = dev.ctx.T_lidarj_lidari *
                   (double(depth[size_t(w)]) * Vec3(dirs[3 * w], dirs[3 * w + 1], dirs[3 * w + 2]));
    REQUIRE(y.x() == Approx(h).epsilon(1e-5));
    REQUIRE(dev.images.range[t] == Approx(y.norm()).epsilon(1e-6));
  }
  // Frame j is closer, so the wall spreads over more pixels than frame i's points fill: holes.
  CHECK(covered > facing / 2);
  CHECK(covered < facing);
  // The pixel looking straight at the wall (elevation 0: row 8; azimuth 0: column W/2) sees
  // it Δx = 3 m closer than frame i's same pixel.
  const size_t centre = size_t(8 * s.width + s.width / 2);
  REQUIRE(dev.images.mask[centre] == 1.f);
  CHECK(depth[centre] - dev.images.range[centre] == Approx(delta.x()).margin(0.05));
}

TEST_CASE("The z-buffer keeps the nearest point; equal ranges go to the smallest source index",
          "[render][reproject]") {
  auto& rt = test::runtime();
  // Frame j has a quarter of frame i's columns: sources in columns 31 and 33 of frame i
  // (azimuth ±2π/64, mirror images) and 32 (azimuth 0) all land in column 8 of frame j, row
  // for row; mirror images at equal depth have bit-equal squared ranges.
  Sensor si;
  si.name = "fine";
  si.height = 8;
  si.width = 64;
  si.fov_up_deg = 2.0;
  si.fov_deg = 16.0;
  Sensor sj = si;
  sj.name = "coarse";
  sj.width = 16;
  const int row = 3;
  const int a = row * si.width + 31, b = row * si.width + 32, c = row * si.width + 33;
  const size_t target = size_t(row * sj.width + 8);
  const Pose T = Pose::Identity();  // T_lidarj_lidari exactly I, so mirror images stay exact
  render::CrossFrameReprojection rp(rt, si, sj, 1.0);
  const auto g = test::ref_reproj_geometry<float>(si, sj, 1.0);
  struct Case {
    float da, db, dc;
    int winner;
  };
  for (const Case& k : {Case{10.f, 10.5f, 10.f, a}, Case{10.f, 10.5f, 9.99f, c},
                        Case{10.f, 9.9f, 10.f, b}, Case{0.f, 10.5f, 10.f, c}}) {
    std::vector<float> depth(size_t(si.height) * si.width, 0.f);
    depth[size_t(a)] = k.da;
    depth[size_t(b)] = k.db;
    depth[size_t(c)] = k.dc;
    const auto dev = test::device_reproject(rp, depth, T, T);
    const auto ref = test::ref_reproject_forward(g, depth, dev.ctx.rows_lidarj_lidari);
    INFO("depths " << k.da << " " << k.db << " " << k.dc);
    CHECK(dev.images.winner[target] == k.winner);
    CHECK(ref.winner[target] == k.winner);
    CHECK(dev.images.range[target] == Approx(depth[size_t(k.winner)]).epsilon(1e-6));
    CHECK(count(dev.images.mask) == 1);
    CHECK(mismatches(dev.images, ref) == 0);
    CHECK(test::sym_rel_err(dev.images.range, ref.range) <= kSqrtUlps);
  }
  // The first case really is a tie in the bits the z-buffer compares.
  std::vector<float> depth(size_t(si.height) * si.width, 0.f);
  float qa = 0, qc = 0;
  const auto rows = render::lidarj_lidari_rows(Pose::Identity());
  REQUIRE(test::ref_target(g, rows, a, 10.f, &qa) == int(target));
  REQUIRE(test::ref_target(g, rows, c, 10.f, &qc) == int(target));
  REQUIRE(bits(qa) == bits(qc));
}

TEST_CASE("Forward is bit-identical from run to run", "[render][reproject]") {
  auto& rt = test::runtime();
  const Dataset& d = test::reproj_pair("kitti360-low-a");
  render::CrossFrameReprojection rp(rt, d.sensor, d.sensor, 1.0);
  const auto first = test::device_reproject(rp, d.frames[0].image.range, d.frames[0].T_world_lidar,
                                            d.frames[1].T_world_lidar);
  for (int run = 0; run < 3; ++run) {
    const auto again = test::device_reproject(rp, d.frames[0].image.range,
                                              d.frames[0].T_world_lidar, d.frames[1].T_world_lidar);
    CHECK(std::memcmp(first.images.range.data(), again.images.range.data(),
                      first.images.range.size() * 4) == 0);
    CHECK(first.images.mask == again.images.mask);
    CHECK(first.images.winner == again.images.winner);
  }
}
