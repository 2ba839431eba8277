// BakedScene checks, geometry and its file (see baked_scene.hpp).
#include "bake/baked_scene.hpp"

#include <cstring>
#include <fstream>

#include "core/error.hpp"

namespace sgnlf::bake {
namespace {

constexpr char kMagic[8] = {'S', 'G', 'N', 'L', 'F', 'B', 'A', 'K'};
constexpr uint32_t kVersion = 1;
static_assert(sizeof(BakedVertex) == 16, "BakedVertex is the kernel's float4");

}  // namespace

void BakedScene::validate(const std::string& where) const {
  const size_t n = size_t(dims[0]) * size_t(dims[1]) * size_t(dims[2]);
  if (dims[0] <= 0 || dims[1] <= 0 || dims[2] <= 0 || index.size() != n)
    throw NumericError(where + ": index holds " + std::to_string(index.size()) +
                       " entries for dims " + std::to_string(dims[0]) + " x " +
                       std::to_string(dims[1]) + " x " + std::to_string(dims[2]));
  if (brick < 1 || !(voxel_m > 0.0f) || !(step_m > 0.0f) || !(far_m > near_m))
    throw NumericError(where + ": bad geometry (brick " + std::to_string(brick) + ", voxel_m " +
                       std::to_string(voxel_m) + ", step_m " + std::to_string(step_m) +
                       ", near_m " + std::to_string(near_m) + ", far_m " + std::to_string(far_m) + ")");
  const size_t V = size_t(vertices_per_brick());
  if (vertices.size() % V != 0)
    throw NumericError(where + ": " + std::to_string(vertices.size()) +
                       " vertices is not a whole number of bricks of " + std::to_string(V));
  const long slots = long(vertices.size() / V);
  for (size_t i = 0; i < n; ++i)
    if (index[i] < -1 || index[i] >= slots)
      throw NumericError(where + ": index[" + std::to_string(i) + "] = " +
                         std::to_string(index[i]) + " outside [-1, " + std::to_string(slots) + ")");
}

std::vector<uint32_t> BakedScene::cell_mask() const {
  const int n1 = brick + 1, V = vertices_per_brick(), W = mask_words();
  std::vector<uint32_t> m(bricks() * size_t(W), 0u);
  for (size_t b = 0; b < bricks(); ++b)
    for (int k = 0; k < brick; ++k)
      for (int j = 0; j < brick; ++j)
        for (int i = 0; i < brick; ++i) {
          bool on = false;
          for (int q = 0; q < 8 && !on; ++q)
            on = vertices[b * size_t(V) +
                          size_t(((k + (q >> 2)) * n1 + j + ((q >> 1) & 1)) * n1 + i + (q & 1))]
                     .logit >= skip_logit;
          const int c = (k * brick + j) * brick + i;
          if (on) m[b * size_t(W) + size_t(c >> 5)] |= 1u << (c & 31);
        }
  return m;
}

std::array<double, 3> BakedScene::vertex_position(const std::array<int, 3>& b, int i, int j,
                                                  int k) const {
  const int v[3] = {i, j, k};
  std::array<double, 3> p{};
  for (size_t a = 0; a < 3; ++a)
    p[a] = origin_m[a] + double(voxel_m) * (double(b[a]) * brick + v[a]);
  return p;
}

void write_baked_scene(const std::string& path, const BakedScene& s) {
  s.validate(path);
  const Json header{{"voxel_m", s.voxel_m},   {"brick", s.brick},
                    {"origin_m", s.origin_m}, {"dims", s.dims},
                    {"near_m", s.near_m},     {"far_m", s.far_m},
                    {"step_m", s.step_m},     {"stop_transmittance", s.stop_transmittance},
                    {"skip_logit", s.skip_logit},
                    {"bricks", s.bricks()},   {"provenance", s.provenance}};
  const std::string text = header.dump();
  std::ofstream out(path, std::ios::binary);
  if (!out) throw IoError(path + ": cannot write the baked scene");
  const uint64_t len = text.size();
  out.write(kMagic, 8);
  out.write(reinterpret_cast<const char*>(&kVersion), 4);
  out.write(reinterpret_cast<const char*>(&len), 8);
  out.write(text.data(), std::streamsize(len));
  out.write(reinterpret_cast<const char*>(s.index.data()), std::streamsize(s.index.size() * 4));
  out.write(reinterpret_cast<const char*>(s.vertices.data()),
            std::streamsize(s.vertices.size() * sizeof(BakedVertex)));
  if (!out) throw IoError(path + ": write failed");
}

BakedScene read_baked_scene(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path + ": cannot open the baked scene");
  char magic[8];
  uint32_t version = 0;
  uint64_t len = 0;
  in.read(magic, 8);
  in.read(reinterpret_cast<char*>(&version), 4);
  in.read(reinterpret_cast<char*>(&len), 8);
  if (!in || std::memcmp(magic, kMagic, 8) != 0)
    throw IoError(path + ": not a baked scene (no SGNLFBAK header; made by `sgnlf bake`)");
  if (version != kVersion)
    throw IoError(path + ": baked scene version " + std::to_string(version) + ", this build reads " +
                  std::to_string(kVersion));
  if (len > (1u << 24)) throw IoError(path + ": header length " + std::to_string(len) + " too large");
  std::string text(len, '\0');
  in.read(text.data(), std::streamsize(len));
  if (!in) throw IoError(path + ": truncated header");
  Json h;
  try {
    h = Json::parse(text);
  } catch (const std::exception& e) {
    throw IoError(path + ": header is not JSON (" + e.what() + ")");
  }
  BakedScene s;
  try {
    s.voxel_m = h.at("voxel_m").get<float>();
    s.brick = h.at("brick").get<int>();
    s.origin_m = h.at("origin_m").get<std::array<double, 3>>();
    s.dims = h.at("dims").get<std::array<int, 3>>();
    s.near_m = h.at("near_m").get<float>();
    s.far_m = h.at("far_m").get<float>();
    s.step_m = h.at("step_m").get<float>();
    s.stop_transmittance = h.at("stop_transmittance").get<float>();
    s.skip_logit = h.at("skip_logit").get<float>();
    s.provenance = h.value("provenance", Json::object());
  } catch (const std::exception& e) {
    throw IoError(path + ": header field missing or of the wrong type (" + e.what() + ")");
  }
  const size_t bricks = h.value("bricks", size_t(0));
  if (s.dims[0] <= 0 || s.dims[1] <= 0 || s.dims[2] <= 0 || s.brick < 1 || s.brick > 64)
    throw IoError(path + ": bad dims or brick in the header");
  const size_t n = size_t(s.dims[0]) * size_t(s.dims[1]) * size_t(s.dims[2]);
  s.index.resize(n);
  s.vertices.resize(bricks * size_t(s.vertices_per_brick()));
  in.read(reinterpret_cast<char*>(s.index.data()), std::streamsize(n * 4));
  in.read(reinterpret_cast<char*>(s.vertices.data()),
          std::streamsize(s.vertices.size() * sizeof(BakedVertex)));
  if (!in) throw IoError(path + ": truncated (index of " + std::to_string(n) + " bricks, " +
                         std::to_string(bricks) + " stored bricks expected)");
  s.validate(path);
  return s;
}

}  // namespace sgnlf::bake
