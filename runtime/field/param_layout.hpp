// One flat float parameter buffer for a whole model (method.md §0 "one flat parameter buffer, one
// Adam kernel"), and a gradient buffer with the same layout. ParamLayout hands out named slices;
// each module (HashGrid, Mlp, ...) initialises and differentiates only its own slice.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

namespace sgnlf::field {

struct ParamSlice {
  std::string name;
  size_t offset = 0;  // in floats from the start of the flat buffer
  size_t count = 0;   // floats
};

class ParamLayout {
 public:
  // Appends a slice of `count` floats; offsets are aligned to `align` floats (default 16 = 64 B,
  // so every slice starts on a cache line and vector loads stay aligned).
  ParamSlice add(const std::string& name, size_t count, size_t align = 16);
  // The slice called `name`; throws sgnlf::Error when absent.
  const ParamSlice& slice(const std::string& name) const;
  const std::vector<ParamSlice>& slices() const { return slices_; }
  // Total floats of the flat buffer (including alignment gaps, which stay zero).
  size_t total() const { return total_; }

 private:
  std::vector<ParamSlice> slices_;
  size_t total_ = 0;
};

}  // namespace sgnlf::field
