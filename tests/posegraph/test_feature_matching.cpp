// The confidence graph's building blocks against brute-force references: mutual feature nearest
// neighbours within a radius (with and without masks), voxel downsampling, candidate pairs, the
// spatial-consistency score and the feature provider checks.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <set>

#include "core/error.hpp"
#include "core/rng.hpp"
#include "posegraph/candidate_pairs.hpp"
#include "posegraph/feature_matching.hpp"
#include "posegraph/spatial_consistency.hpp"
#include "posegraph/standin_features.hpp"
#include "posegraph/voxel_downsample.hpp"
#include "support/cloud_reference.hpp"

using namespace sgnlf;
using namespace sgnlf::posegraph;

namespace {

constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();

// Unit random features (rows drawn from Rng), a few rows repeated so that ties occur.
std::vector<float> random_unit_features(Rng& rng, size_t n, int dim) {
  std::vector<float> f(n * size_t(dim));
  for (size_t r = 0; r < n; ++r) {
    double sq = 0;
    for (int k = 0; k < dim; ++k) {
      f[r * dim + k] = float(rng.normal());
      sq += double(f[r * dim + k]) * f[r * dim + k];
    }
    for (int k = 0; k < dim; ++k) f[r * dim + k] = float(f[r * dim + k] / std::sqrt(sq));
  }
  for (size_t r = 1; r < n; r += 9)
    std::copy(f.begin() + (r - 1) * dim, f.begin() + r * dim, f.begin() + r * dim);
  return f;
}

// Exhaustive: best partner of each active q among the active p within the radius.
std::vector<uint32_t> brute_best(const FeatureCloud& Q, const FeatureCloud& P, float r,
                                 const std::vector<uint8_t>& qa, const std::vector<uint8_t>& pa) {
  std::vector<uint32_t> best(Q.size(), kNone);
  for (uint32_t q = 0; q < Q.size(); ++q) {
    if (!qa.empty() && !qa[q]) continue;
    float bc = -std::numeric_limits<float>::infinity();
    for (uint32_t p = 0; p < P.size(); ++p) {
      if (!pa.empty() && !pa[p]) continue;
      if (geometry::squared_distance(Q.x[q], P.x[p]) > r * r) continue;
      const float c = cosine(Q.row(q), P.row(p), Q.dim);
      if (c > bc) bc = c, best[q] = p;
    }
  }
  return best;
}

std::vector<FeatureMatch> brute_mutual(const FeatureCloud& A, const FeatureCloud& B, float r,
                                       const std::vector<uint8_t>& aa = {},
                                       const std::vector<uint8_t>& ba = {}) {
  const auto ab = brute_best(A, B, r, aa, ba), bb = brute_best(B, A, r, ba, aa);
  std::vector<FeatureMatch> out;
  for (uint32_t a = 0; a < A.size(); ++a)
    if (ab[a] != kNone && bb[ab[a]] == a)
      out.push_back(FeatureMatch{a, ab[a], cosine(A.row(a), B.row(ab[a]), A.dim)});
  return out;
}

void require_same(const std::vector<FeatureMatch>& got, const std::vector<FeatureMatch>& want) {
  REQUIRE(got.size() == want.size());
  for (size_t k = 0; k < got.size(); ++k) {
    REQUIRE(got[k].a == want[k].a);
    REQUIRE(got[k].b == want[k].b);
    REQUIRE(got[k].cosine == want[k].cosine);
  }
}

}  // namespace

TEST_CASE("mutual feature matches equal a brute-force search", "[posegraph][confidence]") {
  Rng rng(21);
  const int dim = 8;
  for (size_t n : {1u, 40u, 600u}) {
    auto xa = test::random_cloud(rng, n, 10.f), xb = test::random_cloud(rng, n + 17, 10.f);
    xb[0] = xa[0];  // a coincident pair
    const FeatureCloud A(xa, random_unit_features(rng, xa.size(), dim), dim);
    const FeatureCloud B(xb, random_unit_features(rng, xb.size(), dim), dim);
    for (float r : {0.f, 0.7f, 2.5f, 50.f}) {
      const auto got = mutual_feature_matches(A, B, r);
      require_same(got, brute_mutual(A, B, r));
      if (r == 50.f) CHECK(!got.empty());
      // Masks restrict queries and partners alike.
      std::vector<uint8_t> ma(A.size()), mb(B.size());
      for (auto& m : ma) m = rng.below(3) != 0;
      for (auto& m : mb) m = rng.below(2) != 0;
      require_same(mutual_feature_matches(A, B, r, ma, mb), brute_mutual(A, B, r, ma, mb));
    }
  }
}

TEST_CASE("mutual feature matches with smooth stand-in features follow the geometry",
          "[posegraph][confidence]") {
  // Same surface points seen twice with a 2 cm jitter: every point's best partner within 1 m
  // is (almost always) its own twin, since the stand-in similarity falls with distance.
  Rng rng(22);
  const auto provider = standin_fourier_features({});
  auto xa = test::random_cloud(rng, 800, 15.f);
  auto xb = xa;
  for (auto& p : xb) p += geometry::Point3f(rng.uniform(-0.02f, 0.02f), rng.uniform(-0.02f, 0.02f), 0.f);
  const FeatureCloud A(xa, unit_features(provider, xa), provider.dim);
  const FeatureCloud B(xb, unit_features(provider, xb), provider.dim);
  const auto m = mutual_feature_matches(A, B, 1.f);
  require_same(m, brute_mutual(A, B, 1.f));
  size_t twins = 0;
  for (const auto& fm : m) twins += fm.a == fm.b;
  CHECK(double(twins) > 0.95 * double(xa.size()));
}

TEST_CASE("mutual feature matches reject inconsistent inputs", "[posegraph][confidence]") {
  const std::vector<geometry::Point3f> x = {geometry::Point3f(0, 0, 0), geometry::Point3f(1, 0, 0)};
  const FeatureCloud A(x, {1, 0, 0, 1}, 2);
  const FeatureCloud B3(x, {1, 0, 0, 0, 1, 0}, 3);
  CHECK_THROWS_AS(mutual_feature_matches(A, B3, 1.f), Error);
  CHECK_THROWS_AS(mutual_feature_matches(A, A, -1.f), Error);
  CHECK_THROWS_AS(mutual_feature_matches(A, A, 1.f, {1}), Error);
  CHECK_THROWS_AS(FeatureCloud(x, {1, 0, 0}, 2), Error);
  CHECK_THROWS_AS(FeatureCloud(x, {}, 0), Error);
}

TEST_CASE("voxel downsampling: one representative per occupied voxel, nearest its centroid",
          "[posegraph][confidence]") {
  Rng rng(23);
  auto x = test::random_cloud(rng, 3000, 20.f);
  x.push_back(x[5]);  // a duplicate: ties keep the lower index
  const double v = 1.5;
  const VoxelGrid g = voxel_downsample(x, v);
  REQUIRE(g.voxel_of.size() == x.size());
  auto key = [&](const geometry::Point3f& p) {
    return std::array<long, 3>{long(std::floor(p.x() / v)), long(std::floor(p.y() / v)),
                               long(std::floor(p.z() / v))};
  };
  std::set<std::array<long, 3>> keys;
  for (const auto& p : x) keys.insert(key(p));
  CHECK(g.voxels() == keys.size());
  for (size_t vi = 0; vi < g.voxels(); ++vi) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    size_t n = 0, first = x.size();
    for (size_t k = 0; k < x.size(); ++k)
      if (g.voxel_of[k] == vi) {
        REQUIRE(key(x[k]) == key(x[g.representative[vi]]));
        c += x[k].cast<double>(), ++n, first = std::min(first, k);
      }
    c /= double(n);
    uint32_t want = 0;
    double best = std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < x.size(); ++k)
      if (g.voxel_of[k] == vi && (x[k].cast<double>() - c).squaredNorm() < best)
        best = (x[k].cast<double>() - c).squaredNorm(), want = uint32_t(k);
    REQUIRE(g.representative[vi] == want);
    if (vi > 0) REQUIRE(first > 0);  // voxels numbered by first appearance
  }
  // Points in different voxels get different voxel numbers.
  for (size_t k = 1; k < x.size(); k += 97)
    REQUIRE((key(x[k]) == key(x[0])) == (g.voxel_of[k] == g.voxel_of[0]));
  CHECK_THROWS_AS(voxel_downsample(x, 0.0), Error);
  CHECK_THROWS_AS(voxel_downsample({geometry::Point3f(1e9f, 0, 0)}, 0.01), Error);
}

TEST_CASE("candidate pairs equal the brute-force distance test plus the sequential pairs",
          "[posegraph][confidence]") {
  Rng rng(24);
  std::vector<Pose> T(60, Pose::Identity());
  for (auto& P : T) P.translation() = Vec3(rng.uniform(-80.f, 80.f), rng.uniform(-80.f, 80.f), 0.0);
  const double D = 25.0;
  const auto got = candidate_pairs(T, {1, 2}, D);
  std::vector<std::pair<int, int>> want, have;
  for (int i = 0; i < 60; ++i)
    for (int j = i + 1; j < 60; ++j) {
      const float d = geometry::squared_distance(T[i].translation().cast<float>(),
                                                 T[j].translation().cast<float>());
      if (j - i <= 2 || d <= float(D) * float(D)) want.emplace_back(i, j);
    }
  for (const auto& c : got) {
    have.emplace_back(c.i, c.j);
    CHECK(c.sequential == (c.j - c.i <= 2));
    CHECK(c.centre_distance_m == (T[c.i].translation() - T[c.j].translation()).norm());
  }
  CHECK(have == want);
  CHECK(have.size() < 60 * 59 / 2);
  // A minimum index gap drops the near non-sequential pairs only.
  for (const auto& c : candidate_pairs(T, {1, 2}, D, 5))
    CHECK((c.sequential || c.j - c.i >= 5));
  size_t with_gap = 0;
  for (const auto& [i, j] : want) with_gap += (j - i <= 2 || j - i >= 5);
  CHECK(candidate_pairs(T, {1, 2}, D, 5).size() == with_gap);
  CHECK_THROWS_AS(candidate_pairs(T, {0}, D), Error);
  CHECK_THROWS_AS(candidate_pairs(T, {1}, -1.0), Error);
}

TEST_CASE("spatial consistency: exact on a small set, deterministic when subsampled",
          "[posegraph][confidence]") {
  const std::vector<Vec3> p = {Vec3(0, 0, 0), Vec3(3, 0, 0), Vec3(0, 4, 0)};
  // q: the same triangle moved rigidly, except that the third point is 1 m off along y.
  const Pose M = exp_se3((Vec6() << 0.1, -0.2, 0.3, 5, 6, 7).finished());
  std::vector<Vec3> q = {M * p[0], M * p[1], M * (p[2] + Vec3(0, 1, 0))};
  const double s = 0.5;
  const double d12 = 5.0 - std::sqrt(9.0 + 25.0);  // ‖p1 − p2‖ − ‖q1 − q2‖
  const double want = (1.0 + std::exp(-1.0 / (2 * s * s)) + std::exp(-d12 * d12 / (2 * s * s))) / 3.0;
  CHECK(spatial_consistency(p, q, s, 100, 1, 0) == Approx(want).epsilon(1e-12));
  CHECK(spatial_consistency({p[0]}, {q[0]}, s, 100, 1, 0) == 0.0);
  CHECK_THROWS_AS(spatial_consistency(p, {q[0]}, s, 100, 1, 0), Error);
  CHECK_THROWS_AS(spatial_consistency(p, q, 0.0, 100, 1, 0), Error);
  // Drawn pairs: the same draws for the same (seed, stream), close to the exact mean.
  Rng rng(25);
  std::vector<Vec3> P, Q;
  for (int k = 0; k < 400; ++k) {
    P.emplace_back(rng.uniform(-20.f, 20.f), rng.uniform(-20.f, 20.f), rng.uniform(-2.f, 2.f));
    Q.push_back(M * P.back() + (k % 4 == 0 ? Vec3(rng.uniform(-3.f, 3.f), 0, 0) : Vec3::Zero()));
  }
  const double exact = spatial_consistency(P, Q, s, 1000000, 1, 0);
  const double drawn = spatial_consistency(P, Q, s, 20000, 1, 7);
  CHECK(drawn == spatial_consistency(P, Q, s, 20000, 1, 7));
  CHECK(drawn != spatial_consistency(P, Q, s, 20000, 1, 8));
  CHECK(drawn == Approx(exact).margin(0.01));
}

TEST_CASE("feature provider output is checked and normalised", "[posegraph][confidence]") {
  const std::vector<Eigen::Vector3f> x = {Eigen::Vector3f(1, 2, 3), Eigen::Vector3f(0, 0, 0)};
  FeatureProvider ok{3, [](const std::vector<Eigen::Vector3f>& p, std::vector<float>& out) {
                       out.clear();
                       for (const auto& v : p) out.insert(out.end(), {v.x(), v.y(), v.z()});
                     }, "identity", {}};
  const auto f = unit_features(ok, x);
  CHECK(f[0] * f[0] + f[1] * f[1] + f[2] * f[2] == Approx(1.0f));
  CHECK(f[3] == 0.f);  // a zero row stays zero
  FeatureProvider short_out = ok;
  short_out.eval = [](const std::vector<Eigen::Vector3f>&, std::vector<float>& out) { out = {1.f}; };
  CHECK_THROWS_AS(unit_features(short_out, x), Error);
  FeatureProvider nan_out = ok;
  nan_out.eval = [](const std::vector<Eigen::Vector3f>& p, std::vector<float>& out) {
    out.assign(p.size() * 3, std::numeric_limits<float>::quiet_NaN());
  };
  CHECK_THROWS_AS(unit_features(nan_out, x), NumericError);
  CHECK_THROWS_AS(unit_features(FeatureProvider{}, x), Error);
  // Parts [2, 1] are normalised on their own: a huge third component no longer dominates.
  FeatureProvider parted{3, [](const std::vector<Eigen::Vector3f>& p, std::vector<float>& out) {
                           out.clear();
                           for (const auto& v : p) out.insert(out.end(), {v.x(), v.y(), 1000.f * v.z()});
                         }, "parted", {2, 1}};
  const std::vector<Eigen::Vector3f> y = {Eigen::Vector3f(1, 0, 1), Eigen::Vector3f(0, 1, 1),
                                          Eigen::Vector3f(3, 4, 0)};
  const auto pf = unit_features(parted, y);
  CHECK(cosine(pf.data(), pf.data() + 3, 3) == Approx(0.5f));  // mean of cosines 0 and 1
  CHECK(pf[0] == Approx(std::sqrt(0.5f)));
  CHECK(pf[6] == Approx(0.6f));  // the zero part is left out: [0.6, 0.8] with unit length
  CHECK(pf[7] == Approx(0.8f));
  CHECK(pf[8] == 0.f);
  const auto whole = unit_features(FeatureProvider{3, parted.eval, "whole", {}}, y);
  CHECK(cosine(whole.data(), whole.data() + 3, 3) > 0.99f);  // without parts the scale dominates
  FeatureProvider bad_parts = parted;
  bad_parts.parts = {2, 2};
  CHECK_THROWS_AS(unit_features(bad_parts, y), Error);
  bad_parts.parts = {3, 0};
  CHECK_THROWS_AS(unit_features(bad_parts, y), Error);
  // The stand-in: unit rows, similarity ≈ 1 nearby and lower metres away.
  const auto s = standin_fourier_features({});
  const auto g = unit_features(s, {Eigen::Vector3f(0, 0, 0), Eigen::Vector3f(0.05f, 0, 0),
                                   Eigen::Vector3f(3, 0, 0)});
  CHECK(cosine(g.data(), g.data() + s.dim, s.dim) > 0.99f);
  CHECK(cosine(g.data(), g.data() + 2 * s.dim, s.dim) < 0.8f);
  StandinFeatureConfig bad;
  bad.max_wavelength_m = 0.5;
  CHECK_THROWS_AS(standin_fourier_features(bad), ConfigError);
}
