// Surface nets over a baked scene and its PLY (see surface_mesh.hpp).
#include "bake/surface_mesh.hpp"

#include <cmath>
#include <cstdint>
#include <fstream>
#include <optional>
#include <unordered_map>

#include "core/error.hpp"

namespace sgnlf::bake {
namespace {

using Vec3i = std::array<long, 3>;

uint64_t cell_key(const Vec3i& c) {
  return (uint64_t(c[2] & 0x1FFFFF) << 42) | (uint64_t(c[1] & 0x1FFFFF) << 21) | uint64_t(c[0] & 0x1FFFFF);
}

// Global vertex lattice lookup: a vertex on a brick face is stored in both bricks (the same
// value), so any stored brick holding it answers.
class Lattice {
 public:
  explicit Lattice(const BakedScene& s) : s_(s), n1_(s.brick + 1) {}
  const BakedVertex* at(const Vec3i& g) const {
    long b[3], l[3];
    for (int a = 0; a < 3; ++a) b[a] = g[size_t(a)] / s_.brick, l[a] = g[size_t(a)] % s_.brick;
    for (int m = 0; m < 8; ++m) {
      long bb[3], ll[3];
      bool ok = true;
      for (int a = 0; a < 3; ++a) {
        const bool down = (m >> a) & 1;
        if (down && l[a] != 0) ok = false;
        bb[a] = down ? b[a] - 1 : b[a];
        ll[a] = down ? s_.brick : l[a];
        if (bb[a] < 0 || bb[a] >= s_.dims[size_t(a)]) ok = false;
      }
      if (!ok) continue;
      const int slot = s_.index[size_t((bb[2] * s_.dims[1] + bb[1]) * s_.dims[0] + bb[0])];
      if (slot < 0) continue;
      return &s_.vertices[size_t(slot) * size_t(s_.vertices_per_brick()) +
                          size_t((ll[2] * n1_ + ll[1]) * n1_ + ll[0])];
    }
    return nullptr;
  }

 private:
  const BakedScene& s_;
  long n1_;
};

}  // namespace

float surface_level(const BakedScene& s) { return std::log(std::log(2.0f) / s.voxel_m); }

SurfaceMesh extract_surface(const BakedScene& s, float level) {
  s.validate();
  const Lattice lat(s);
  SurfaceMesh m;
  std::unordered_map<uint64_t, int> cell_vertex;
  const int B = s.brick;
  // Corner c of a cell: offsets (c & 1, c >> 1 & 1, c >> 2 & 1); its 12 edges as corner pairs.
  static const int kEdges[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3},
                                    {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  std::vector<Vec3i> bricks;
  for (int k = 0; k < s.dims[2]; ++k)
    for (int j = 0; j < s.dims[1]; ++j)
      for (int i = 0; i < s.dims[0]; ++i)
        if (s.index[(size_t(k) * size_t(s.dims[1]) + size_t(j)) * size_t(s.dims[0]) + size_t(i)] >= 0)
          bricks.push_back({i, j, k});
  // Vertices: one per cell with corners on both sides of the level.
  for (const Vec3i& b : bricks)
    for (int ck = 0; ck < B; ++ck)
      for (int cj = 0; cj < B; ++cj)
        for (int ci = 0; ci < B; ++ci) {
          const Vec3i c{b[0] * B + ci, b[1] * B + cj, b[2] * B + ck};
          const BakedVertex* v[8];
          int inside = 0;
          for (int q = 0; q < 8; ++q) {
            v[q] = lat.at({c[0] + (q & 1), c[1] + ((q >> 1) & 1), c[2] + ((q >> 2) & 1)});
            inside += v[q]->logit > level;
          }
          if (inside == 0 || inside == 8) continue;
          double p[3] = {0, 0, 0}, inten = 0.0, ret = 0.0;
          int crossings = 0;
          for (const auto& e : kEdges) {
            const BakedVertex *a = v[e[0]], *bv = v[e[1]];
            if ((a->logit > level) == (bv->logit > level)) continue;
            const double f = (double(level) - a->logit) / (double(bv->logit) - a->logit);
            for (int ax = 0; ax < 3; ++ax)
              p[ax] += ((e[0] >> ax) & 1) + f * (((e[1] >> ax) & 1) - ((e[0] >> ax) & 1));
            inten += a->intensity + f * (bv->intensity - a->intensity);
            ret += a->ret + f * (bv->ret - a->ret);
            ++crossings;
          }
          cell_vertex[cell_key(c)] = int(m.intensity.size());
          for (int ax = 0; ax < 3; ++ax)
            m.xyz.push_back(float(s.origin_m[size_t(ax)] +
                                  s.voxel_m * (double(c[size_t(ax)]) + p[ax] / crossings)));
          m.intensity.push_back(float(inten / crossings));
          m.drop.push_back(float(1.0 - ret / crossings));
        }
  // Faces: each lattice edge (from a vertex of a stored brick, local coordinates < brick) whose
  // ends straddle the level joins the four cells around it.
  for (const Vec3i& b : bricks)
    for (int lk = 0; lk < B; ++lk)
      for (int lj = 0; lj < B; ++lj)
        for (int li = 0; li < B; ++li) {
          const Vec3i g{b[0] * B + li, b[1] * B + lj, b[2] * B + lk};
          const BakedVertex* v0 = lat.at(g);
          for (int ax = 0; ax < 3; ++ax) {
            Vec3i g1 = g;
            ++g1[size_t(ax)];
            const BakedVertex* v1 = lat.at(g1);
            if (!v1 || (v0->logit > level) == (v1->logit > level)) continue;
            const int u = (ax + 1) % 3, w = (ax + 2) % 3;
            int q[4];
            bool all = true;
            const long du[4] = {-1, 0, 0, -1}, dw[4] = {-1, -1, 0, 0};
            for (int t = 0; t < 4 && all; ++t) {
              Vec3i c = g;
              c[size_t(u)] += du[t], c[size_t(w)] += dw[t];
              const auto it = cell_vertex.find(cell_key(c));
              if (it == cell_vertex.end()) all = false;
              else q[t] = it->second;
            }
            if (!all) continue;
            // The cycle is counter-clockwise seen from +axis: the outward side when v0 is the
            // dense end; otherwise reverse it.
            if (!(v0->logit > level)) std::swap(q[1], q[3]);
            m.triangles.push_back({q[0], q[1], q[2]});
            m.triangles.push_back({q[0], q[2], q[3]});
          }
        }
  return m;
}

void write_surface_ply(const std::string& path, const SurfaceMesh& m) {
  const size_t n = m.intensity.size();
  require(m.xyz.size() == 3 * n && m.drop.size() == n, "write_surface_ply: attribute sizes differ");
  std::ofstream out(path, std::ios::binary);
  if (!out) throw IoError(path + ": cannot write the surface mesh");
  out << "ply\nformat binary_little_endian 1.0\ncomment sgnlf bake: baked surface, world metres\n"
      << "element vertex " << n << "\nproperty float x\nproperty float y\nproperty float z\n"
      << "property float intensity\nproperty float drop_probability\n"
      << "element face " << m.triangles.size() << "\nproperty list uchar int vertex_indices\n"
      << "end_header\n";
  for (size_t p = 0; p < n; ++p) {
    const float rec[5] = {m.xyz[3 * p], m.xyz[3 * p + 1], m.xyz[3 * p + 2], m.intensity[p], m.drop[p]};
    out.write(reinterpret_cast<const char*>(rec), sizeof rec);
  }
  for (const auto& t : m.triangles) {
    const uint8_t three = 3;
    out.write(reinterpret_cast<const char*>(&three), 1);
    out.write(reinterpret_cast<const char*>(t.data()), 12);
  }
  if (!out) throw IoError(path + ": write failed");
}

}  // namespace sgnlf::bake
