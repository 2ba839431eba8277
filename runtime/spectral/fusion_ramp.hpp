// The fusion weight λ(t) of the hybrid feature [f_geo, λ(t)·Ψ(x)] (method.md §4.1): 0 until
// `start`, linear to 1 at `end`. Host-only config (the config's "spectral"."fusion"); the fusion
// itself is spectral/fusion.hpp.
#pragma once
#include <string>

#include "core/config_fwd.hpp"

namespace sgnlf::spectral {

struct FusionRamp {
  int start = 0;     // iteration where λ starts to grow from 0
  int end = 2000;    // iteration where λ reaches 1 (end == start: a step)
  double lambda(int iteration) const;
  // The keys and ranges (core/config_fields.hpp); end's range [start, 1e8] is validate()'s.
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("start", s.start, 0, 100000000);
    v("end", s.end);
  }
  void validate() const;
  static FusionRamp from_json(const Json& j, const std::string& where);
  Json to_json() const;
};

}  // namespace sgnlf::spectral
