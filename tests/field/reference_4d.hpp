// Host references of LiDAR4D's 4D encodings (tests only; the runtime never calls them): the
// K-Planes planes (runtime/field/kplanes.hpp) and the time-sliced 2D hash grids
// (runtime/field/time_hash_grid.hpp). Plain loops in the order the formulas read, in double.
#pragma once
#include <vector>

#include "field/kplanes.hpp"
#include "field/time_hash_grid.hpp"

namespace sgnlf::test::ref {

// table = the module slice; x N × 3, t N; enc / d_enc N × n_output(groups).
std::vector<float> kplanes_fwd(const field::KPlanesConfig& cfg, const std::vector<float>& table,
                               const std::vector<float>& x, const std::vector<float>& t,
                               field::PlaneGroups groups);
// dL/dparams over the whole slice (zero on the planes of the groups not computed).
std::vector<float> kplanes_bwd(const field::KPlanesConfig& cfg, const std::vector<float>& table,
                               const std::vector<float>& x, const std::vector<float>& t,
                               const std::vector<float>& d_enc, field::PlaneGroups groups);
std::vector<float> kplanes_bwd_dx(const field::KPlanesConfig& cfg,
                                  const std::vector<float>& table, const std::vector<float>& x,
                                  const std::vector<float>& t, const std::vector<float>& d_enc,
                                  field::PlaneGroups groups);

std::vector<float> time_hash_fwd(const field::TimeHashGridConfig& cfg,
                                 const std::vector<float>& table, const std::vector<float>& x,
                                 const std::vector<float>& t);
std::vector<float> time_hash_bwd(const field::TimeHashGridConfig& cfg,
                                 const std::vector<float>& table, const std::vector<float>& x,
                                 const std::vector<float>& t, const std::vector<float>& d_enc);
std::vector<float> time_hash_bwd_dx(const field::TimeHashGridConfig& cfg,
                                    const std::vector<float>& table, const std::vector<float>& x,
                                    const std::vector<float>& t, const std::vector<float>& d_enc);

}  // namespace sgnlf::test::ref
