// Cross-frame reprojection, bad input: wrong buffer sizes, negative and non-finite depths,
// non-rigid or non-finite poses, unusable sensors and range scales each throw an error that
// names the bad value.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "reproject_test_data.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;
using Catch::Matchers::Contains;

namespace {
Sensor small_sensor() {
  Sensor s;
  s.name = "small";
  s.height = 8;
  s.width = 64;
  s.fov_up_deg = 2.0;
  s.fov_deg = 16.0;
  return s;
}
}  // namespace

TEST_CASE("Reprojection rejects buffers of the wrong size", "[render][reproject][errors]") {
  auto& rt = test::runtime();
  const Sensor s = small_sensor();
  Sensor big = s;
  big.width = 128;
  render::CrossFrameReprojection rp(rt, s, s, 1.0), rp_big(rt, big, big, 1.0);
  const size_t n = size_t(s.height) * s.width;
  auto depth = cl::Buffer::from(rt, std::vector<float>(n, 10.f));
  auto short_depth = cl::Buffer::from(rt, std::vector<float>(n - 1, 10.f));
  auto out = rp.make_output();
  auto out_big = rp_big.make_output();
  const Pose I = Pose::Identity();
  CHECK_THROWS_WITH(rp.forward(short_depth, I, I, out), Contains("depth_i") && Contains("needs 512"));
  CHECK_THROWS_WITH(rp_big.forward(depth, I, I, out_big), Contains("depth_i (8 x 128)"));
  auto out_small = rp.make_output();
  CHECK_THROWS_WITH(rp_big.forward(cl::Buffer::from(rt, std::vector<float>(2 * n, 1.f)), I, I, out_small),
                    Contains("range (D_ij)"));
  const auto ctx = rp.forward(depth, I, I, out);
  auto grad = cl::Buffer::from(rt, std::vector<float>(n - 8, 1.f));
  cl::Buffer grad_depth(rt, n * 4), short_grad_depth(rt, (n - 1) * 4);
  auto full_grad = cl::Buffer::from(rt, std::vector<float>(n, 1.f));
  CHECK_THROWS_WITH(rp.backward(ctx, depth, out, grad, grad_depth, Vec6::Zero(), Vec6::Zero()),
                    Contains("grad_range") && Contains("8 x 64"));
  CHECK_THROWS_WITH(rp.backward(ctx, depth, out, full_grad, short_grad_depth, Vec6::Zero(), Vec6::Zero()),
                    Contains("grad_depth_i"));
  Vec6 bad_xi = Vec6::Zero();
  bad_xi[2] = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(rp.backward(ctx, depth, out, full_grad, grad_depth, bad_xi, Vec6::Zero()),
                  NumericError);
  // The valid call still works after the rejected ones.
  CHECK_NOTHROW(rp.backward(ctx, depth, out, full_grad, grad_depth, Vec6::Zero(), Vec6::Zero()));
}

TEST_CASE("Reprojection reports a NaN, infinite or negative depth by its pixel",
          "[render][reproject][errors]") {
  auto& rt = test::runtime();
  const Sensor s = small_sensor();
  render::CrossFrameReprojection rp(rt, s, s, 1.0);
  const size_t n = size_t(s.height) * s.width;
  const Pose I = Pose::Identity();
  struct Bad {
    float value;
    const char* text;
  };
  for (const Bad& b : {Bad{std::numeric_limits<float>::quiet_NaN(), "nan"},
                       Bad{std::numeric_limits<float>::infinity(), "inf"}, Bad{-2.5f, "-2.5"}}) {
    std::vector<float> host(n, 10.f);
    host[size_t(3 * s.width + 5)] = b.value;
    host[size_t(6 * s.width + 1)] = b.value;  // a later bad pixel: the first one is named
    auto depth = cl::Buffer::from(rt, host);
    auto out = rp.make_output();
    const auto ctx = rp.forward(depth, I, I, out);
    INFO(b.text);
    CHECK_THROWS_AS(rp.read(out), NumericError);
    CHECK_THROWS_WITH(rp.read(out), Contains("row 3, col 5") && Contains(b.text));
    auto grad = cl::Buffer::from(rt, std::vector<float>(n, 1.f));
    cl::Buffer grad_depth(rt, n * 4);
    CHECK_THROWS_WITH(rp.backward(ctx, depth, out, grad, grad_depth, Vec6::Zero(), Vec6::Zero()),
                      Contains("row 3, col 5"));
  }
  // Zero is "no depth", not an error; the next forward clears an earlier error.
  auto depth = cl::Buffer::from(rt, std::vector<float>(n, 0.f));
  auto out = rp.make_output();
  rp.forward(depth, I, I, out);
  const auto img = rp.read(out);
  for (float m : img.mask) REQUIRE(m == 0.f);
}

TEST_CASE("Reprojection rejects non-rigid and non-finite poses", "[render][reproject][errors]") {
  auto& rt = test::runtime();
  const Sensor s = small_sensor();
  render::CrossFrameReprojection rp(rt, s, s, 1.0);
  const size_t n = size_t(s.height) * s.width;
  auto depth = cl::Buffer::from(rt, std::vector<float>(n, 10.f));
  auto out = rp.make_output();
  const Pose good = test::make_pose(Vec3(0.1, 0.2, 0.3), Vec3(1, 2, 3));
  Pose scaled = good;
  scaled.linear() *= 1.01;
  Pose mirrored = good;
  mirrored.linear().col(0) *= -1.0;
  Pose sheared = good;
  sheared.linear()(0, 1) += 1e-3;
  Pose bottom = good;
  bottom.matrix()(3, 0) = 0.5;
  Pose nan = good;
  nan.translation().x() = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(rp.forward(depth, scaled, good, out),
                    Contains("T_world_lidar_i is not a rigid transform") && Contains("0.0201"));
  CHECK_THROWS_WITH(rp.forward(depth, good, mirrored, out),
                    Contains("T_world_lidar_j") && Contains("det R = -1"));
  CHECK_THROWS_WITH(rp.forward(depth, sheared, good, out), Contains("RᵀR − I"));
  CHECK_THROWS_WITH(rp.forward(depth, good, bottom, out), Contains("bottom row"));
  CHECK_THROWS_AS(rp.forward(depth, nan, good, out), NumericError);
  CHECK_THROWS_WITH(rp.forward(depth, nan, good, out), Contains("T_world_lidar_i is not finite"));
  CHECK_NOTHROW(rp.forward(depth, good, good, out));
}

TEST_CASE("Reprojection rejects unusable sensors and range scales", "[render][reproject][errors]") {
  auto& rt = test::runtime();
  const Sensor s = small_sensor();
  Sensor narrow = s;
  narrow.width = 4;
  CHECK_THROWS_AS(render::CrossFrameReprojection(rt, s, narrow, 1.0), ConfigError);
  CHECK_THROWS_WITH(render::CrossFrameReprojection(rt, s, narrow, 1.0), Contains("width 4"));
  Sensor bad = s;
  bad.fov_deg = -3;
  CHECK_THROWS_AS(render::CrossFrameReprojection(rt, bad, s, 1.0), ConfigError);
  CHECK_THROWS_WITH(render::CrossFrameReprojection(rt, s, s, 0.0), Contains("range_scale = 0"));
  CHECK_THROWS_AS(render::CrossFrameReprojection(rt, s, s, std::nan("")), ConfigError);
}
