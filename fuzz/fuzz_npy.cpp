// .npy range arrays (sgnlf render's output, read back by tools and tests): io::read_range_npy.
#include "core/error.hpp"
#include "fuzz_input.hpp"
#include "io/range_array.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = sgnlf::fuzz::write_input("range.npy", data, size);
  try {
    const sgnlf::RangeImage img = sgnlf::io::read_range_npy(path);
    if (img.range.size() != img.size()) __builtin_trap();
  } catch (const sgnlf::Error&) {
  }
  return 0;
}
