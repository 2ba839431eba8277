// The simulated sequence the pipeline benchmarks train on: `frames` frames of a built-in
// sequence at full sensor size, simulated once per process (single-threaded, fixed seed).
#pragma once
#include <map>
#include <string>
#include <utility>

#include "datasets/simulate.hpp"

namespace sgnlf::bench {

inline const Dataset& simulated_dataset(const std::string& sequence, int frames) {
  static std::map<std::pair<std::string, int>, Dataset> cache;
  auto it = cache.find({sequence, frames});
  if (it == cache.end()) {
    SimOptions o;
    o.sequence = sequence;
    o.frames = frames;
    o.threads = 1;
    it = cache.emplace(std::make_pair(sequence, frames), simulate(o).dataset).first;
  }
  return it->second;
}

}  // namespace sgnlf::bench
