// SHA-256 (FIPS 180-4) of a file, for tests that pin data files by hash: the in-repo real sample
// (datasets/real-sample/README.md lists a `sha256sum` line per scan). Tests only; the runtime
// never hashes files.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace sgnlf::test {

// Lower-case hex digest of `bytes`.
std::string sha256_hex(const std::vector<uint8_t>& bytes);
// Lower-case hex digest of the file's bytes; REQUIREs that the file can be read.
std::string sha256_file(const std::string& path);

}  // namespace sgnlf::test
