// Replays files through a fuzz target's LLVMFuzzerTestOneInput without libFuzzer: every file of
// the folders given on the command line (the committed seed corpus and the inputs of crashes
// already found and fixed, fuzz/regressions/<target>/). Built with the ordinary compiler as a
// CTest test per target (tests/fuzz), so the fixed crashes stay fixed in every test run, with
// or without the sanitizers. Exits non-zero when a folder holds no file; a crash is a crash.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  size_t n = 0;
  for (int a = 1; a < argc; ++a) {
    if (!fs::is_directory(argv[a])) continue;  // a target without regressions yet
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(argv[a]))
      if (e.is_regular_file()) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    for (const auto& f : files) {
      std::ifstream in(f, std::ios::binary);
      const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      std::printf("replay %s (%zu bytes)\n", f.string().c_str(), bytes.size());
      std::fflush(stdout);
      LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
      ++n;
    }
  }
  std::printf("%zu inputs replayed without a crash\n", n);
  return n > 0 ? 0 : 1;
}
