// Shared by the fuzz targets: the parsers under test read files, so each input is written to a
// file of this process (under $TMPDIR, or /dev/shm when it exists) and read back through the
// project's own path-based API. Project errors (sgnlf::Error and its kinds) are the expected
// outcome of bad input; anything else escaping a parser (a JSON type_error, std::out_of_range,
// bad_alloc, filesystem_error) is a finding: the target lets it propagate and libFuzzer reports
// it as a crash with the input that caused it.
#pragma once
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace sgnlf::fuzz {

inline std::string scratch_dir() {
  static const std::string dir = [] {
    namespace fs = std::filesystem;
    const char* t = std::getenv("TMPDIR");
    fs::path base = t && *t ? fs::path(t) : fs::exists("/dev/shm") ? fs::path("/dev/shm") : fs::temp_directory_path();
    const fs::path d = base / ("sgnlf-fuzz-" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d.string();
  }();
  return dir;
}

// Writes the input to <scratch>/<name> and returns the path.
inline std::string write_input(const std::string& name, const uint8_t* data, size_t size) {
  const std::string path = scratch_dir() + "/" + name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  return path;
}

}  // namespace sgnlf::fuzz
