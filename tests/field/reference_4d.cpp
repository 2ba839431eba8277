// Host references of the 4D encodings (tests only). Both encodings are, per point and output
// unit (a scale and group of the planes, a level of the time hash), the Hadamard product of
// three interpolated samples; a sample is a list of (entry, weight, ∂weight/∂pos_a,
// ∂weight/∂pos_b) terms over the module slice. Positions are computed in float with the
// kernels' operations (so both pick the same cell); everything after that in double.
#include "reference_4d.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace sgnlf::test::ref {
namespace {

struct Term {
  size_t e;
  double w, wa, wb;
};
struct Sample {
  std::vector<Term> terms;
  int a = 0, b = 0;          // axes (3 = time: not differentiated)
  double fa = 0, fb = 0;     // ∂pos_a/∂x_a, ∂pos_b/∂x_b
};
using Unit = std::array<Sample, 3>;  // the three factors of one output unit

// Bilinear terms of the cell at fractions (fa, fb), weighted by ws; idx(da, db) = entry.
template <typename Idx>
void add_bilinear(Sample& s, float fra, float frb, double ws, Idx idx) {
  for (int c = 0; c < 4; ++c) {
    const int da = c & 1, db = c >> 1;
    const double wa1 = da ? fra : 1.0 - fra, wb1 = db ? frb : 1.0 - frb;
    s.terms.push_back({idx(da, db), ws * wa1 * wb1, ws * (da ? 1.0 : -1.0) * wb1,
                       ws * wa1 * (db ? 1.0 : -1.0)});
  }
}

// Per point, the units in output-column order.
std::vector<std::vector<Unit>> kplanes_units(const field::KPlanesConfig& cfg,
                                             const std::vector<float>& x,
                                             const std::vector<float>& t,
                                             field::PlaneGroups groups) {
  static const int axis_a[6] = {0, 0, 1, 0, 1, 2}, axis_b[6] = {1, 2, 2, 3, 3, 3};
  const auto planes = field::kplanes_layout(cfg);
  const int g0 = groups == field::PlaneGroups::Dynamic ? 1 : 0;
  const int ng = groups == field::PlaneGroups::Both ? 2 : 1;
  const size_t n = t.size();
  std::vector<std::vector<Unit>> out(n);
  for (size_t i = 0; i < n; ++i)
    for (int gi = 0; gi < ng; ++gi)
      for (int s = 0; s < cfg.scales; ++s) {
        Unit u;
        for (int k = 0; k < 3; ++k) {
          const int p = 3 * (g0 + gi) + k;
          const auto& pl = planes[size_t(s * 6 + p)];
          Sample& sm = u[size_t(k)];
          sm.a = axis_a[p];
          sm.b = axis_b[p];
          float pos[2], fr[2];
          uint32_t cell[2];
          double fac[2];
          const int axes[2] = {sm.a, sm.b};
          const uint32_t res[2] = {pl.width, pl.height};
          for (int d = 0; d < 2; ++d) {
            const float span = float(res[d] - 1);
            if (axes[d] == 3) {
              pos[d] = std::clamp(t[i], 0.0f, 1.0f) * span;
              fac[d] = 0;
            } else {
              const float v = x[3 * i + size_t(axes[d])];
              pos[d] = (std::clamp(v, -1.0f, 1.0f) + 1.0f) * 0.5f * span;
              fac[d] = (v > -1.0f && v < 1.0f) ? 0.5 * span : 0.0;
            }
            cell[d] = std::min(uint32_t(std::floor(pos[d])), res[d] - 2);
            fr[d] = pos[d] - float(cell[d]);
          }
          sm.fa = fac[0];
          sm.fb = fac[1];
          add_bilinear(sm, fr[0], fr[1], 1.0, [&](int da, int db) {
            return size_t(pl.offset) + (cell[0] + da) + size_t(cell[1] + db) * pl.width;
          });
        }
        out[i].push_back(u);
      }
  return out;
}

uint32_t index2(uint32_t gx, uint32_t gy, const field::HashGridLevel& lv) {
  if (lv.hashed) return (gx ^ (gy * 2654435761u)) & (lv.size - 1u);
  const uint32_t r1 = lv.res - 1;
  return std::min(gx, r1) + std::min(gy, r1) * lv.res;
}

std::vector<std::vector<Unit>> time_hash_units(const field::TimeHashGridConfig& cfg,
                                               const std::vector<float>& x,
                                               const std::vector<float>& t) {
  static const int axis_a[3] = {0, 0, 1}, axis_b[3] = {1, 2, 2};
  const auto planes = field::time_hash_grid_planes(cfg);
  const int T = cfg.time_slices;
  const size_t n = t.size();
  std::vector<std::vector<Unit>> out(n);
  for (size_t i = 0; i < n; ++i) {
    const float u = std::clamp(t[i], 0.0f, 1.0f) * float(T - 1);
    const int s0 = std::min(int(std::floor(u)), T - 1), s1 = std::min(s0 + 1, T - 1);
    const float w1 = u - float(s0);
    for (int l = 0; l < cfg.levels; ++l) {
      Unit un;
      for (int p = 0; p < 3; ++p) {
        const auto& pl = planes[size_t(p)];
        const auto& lv = pl.levels[size_t(l)];
        Sample& sm = un[size_t(p)];
        sm.a = axis_a[p];
        sm.b = axis_b[p];
        sm.fa = sm.fb = 0.5 * double(lv.scale);
        uint32_t g[2];
        float fr[2];
        const int axes[2] = {sm.a, sm.b};
        for (int d = 0; d < 2; ++d) {
          const float x01 = std::fma(x[3 * i + size_t(axes[d])], 0.5f, 0.5f);
          const float pos = std::fma(x01, lv.scale, 0.5f);
          const float fl = std::floor(pos);
          g[d] = uint32_t(int32_t(fl));
          fr[d] = pos - fl;
        }
        const int slices[2] = {s0, s1};
        const double ws[2] = {1.0 - double(w1), double(w1)};
        for (int k = 0; k < 2; ++k)
          add_bilinear(sm, fr[0], fr[1], ws[k], [&](int da, int db) {
            return size_t(pl.offset) + size_t(slices[k]) * pl.slice_entries + lv.offset +
                   index2(g[0] + uint32_t(da), g[1] + uint32_t(db), lv);
          });
      }
      out[i].push_back(un);
    }
  }
  return out;
}

double value(const Sample& s, const std::vector<float>& table, int F, int f) {
  double v = 0;
  for (const auto& tm : s.terms) v += tm.w * table[tm.e * size_t(F) + size_t(f)];
  return v;
}

std::vector<float> product_fwd(const std::vector<std::vector<Unit>>& units,
                               const std::vector<float>& table, int F) {
  std::vector<float> enc;
  for (const auto& point : units)
    for (const auto& u : point)
      for (int f = 0; f < F; ++f)
        enc.push_back(float(value(u[0], table, F, f) * value(u[1], table, F, f) *
                            value(u[2], table, F, f)));
  return enc;
}

// Gradient of Σ d_enc · enc with respect to the table (grad != nullptr) or to x (dx).
void product_bwd(const std::vector<std::vector<Unit>>& units, const std::vector<float>& table,
                 int F, const std::vector<float>& d_enc, std::vector<double>* grad,
                 std::vector<double>* dx) {
  size_t col = 0;
  for (size_t i = 0; i < units.size(); ++i)
    for (const auto& u : units[i])
      for (int f = 0; f < F; ++f, ++col) {
        const double v[3] = {value(u[0], table, F, f), value(u[1], table, F, f),
                             value(u[2], table, F, f)};
        for (int k = 0; k < 3; ++k) {
          const double g = d_enc[col] * v[k == 0 ? 1 : 0] * v[k == 2 ? 1 : 2];
          const Sample& s = u[size_t(k)];
          double da = 0, db = 0;
          for (const auto& tm : s.terms) {
            if (grad) (*grad)[tm.e * size_t(F) + size_t(f)] += tm.w * g;
            da += tm.wa * table[tm.e * size_t(F) + size_t(f)];
            db += tm.wb * table[tm.e * size_t(F) + size_t(f)];
          }
          if (dx && s.a < 3) (*dx)[3 * i + size_t(s.a)] += g * da * s.fa;
          if (dx && s.b < 3) (*dx)[3 * i + size_t(s.b)] += g * db * s.fb;
        }
      }
}

std::vector<float> to_float(const std::vector<double>& v) { return {v.begin(), v.end()}; }

}  // namespace

std::vector<float> kplanes_fwd(const field::KPlanesConfig& cfg, const std::vector<float>& table,
                               const std::vector<float>& x, const std::vector<float>& t,
                               field::PlaneGroups groups) {
  return product_fwd(kplanes_units(cfg, x, t, groups), table, cfg.features);
}

std::vector<float> kplanes_bwd(const field::KPlanesConfig& cfg, const std::vector<float>& table,
                               const std::vector<float>& x, const std::vector<float>& t,
                               const std::vector<float>& d_enc, field::PlaneGroups groups) {
  std::vector<double> g(table.size(), 0.0);
  product_bwd(kplanes_units(cfg, x, t, groups), table, cfg.features, d_enc, &g, nullptr);
  return to_float(g);
}

std::vector<float> kplanes_bwd_dx(const field::KPlanesConfig& cfg,
                                  const std::vector<float>& table, const std::vector<float>& x,
                                  const std::vector<float>& t, const std::vector<float>& d_enc,
                                  field::PlaneGroups groups) {
  std::vector<double> dx(x.size(), 0.0);
  product_bwd(kplanes_units(cfg, x, t, groups), table, cfg.features, d_enc, nullptr, &dx);
  return to_float(dx);
}

std::vector<float> time_hash_fwd(const field::TimeHashGridConfig& cfg,
                                 const std::vector<float>& table, const std::vector<float>& x,
                                 const std::vector<float>& t) {
  return product_fwd(time_hash_units(cfg, x, t), table, cfg.features);
}

std::vector<float> time_hash_bwd(const field::TimeHashGridConfig& cfg,
                                 const std::vector<float>& table, const std::vector<float>& x,
                                 const std::vector<float>& t, const std::vector<float>& d_enc) {
  std::vector<double> g(table.size(), 0.0);
  product_bwd(time_hash_units(cfg, x, t), table, cfg.features, d_enc, &g, nullptr);
  return to_float(g);
}

std::vector<float> time_hash_bwd_dx(const field::TimeHashGridConfig& cfg,
                                    const std::vector<float>& table, const std::vector<float>& x,
                                    const std::vector<float>& t, const std::vector<float>& d_enc) {
  std::vector<double> dx(x.size(), 0.0);
  product_bwd(time_hash_units(cfg, x, t), table, cfg.features, d_enc, nullptr, &dx);
  return to_float(dx);
}

}  // namespace sgnlf::test::ref
