// Training checkpoints: pipeline::load_checkpoint. The file ends in an FNV-1a checksum of the
// rest, which random mutations would almost never match; the target rewrites the last 8 bytes
// to the checksum of the others for inputs that start with byte 0x01 (dropped), so that the body
// parser (array counts, name lengths, sizes) is reached, and reads any other input as it is.
#include <cstring>
#include <string>

#include "core/config.hpp"
#include "core/error.hpp"
#include "fuzz_input.hpp"
#include "pipeline/train/checkpoint.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  if (size > 17 && data[0] == 1) {
    bytes = bytes.substr(1);
    const uint64_t h = sgnlf::fnv1a64(bytes.substr(0, bytes.size() - 8));
    std::memcpy(bytes.data() + bytes.size() - 8, &h, 8);
  }
  const std::string path = sgnlf::fuzz::write_input(
      "latest.ckpt", reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  try {
    const auto ck = sgnlf::pipeline::load_checkpoint(path);
    for (const auto& [name, v] : ck.arrays)
      if (name.size() > bytes.size() || v.size() * 4 > bytes.size()) __builtin_trap();
  } catch (const sgnlf::Error&) {
  }
  return 0;
}
