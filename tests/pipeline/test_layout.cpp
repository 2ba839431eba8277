// runtime/pipeline/ is layered: methods/ → config/ → model/ → train/ → run/. A file includes
// only headers of its own folder and of the folders before it (README "Layout"); a subfolder
// belongs to its layer.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

TEST_CASE("pipeline folders include only the layers above them", "[pipeline][layout]") {
  const std::vector<std::string> order = {"methods", "config", "model", "train", "run"};
  const fs::path root = fs::path(SGNLF_SOURCE_DIR) / "runtime" / "pipeline";
  const std::regex inc(R"re(#include "pipeline/([a-z_]+)/)re");
  int files = 0;
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    const auto ext = e.path().extension();
    if (ext != ".cpp" && ext != ".hpp") continue;
    // The layer is the first folder below runtime/pipeline/ (model/samplers/ is model's).
    const std::string folder = fs::relative(e.path(), root).begin()->string();
    const auto self = std::find(order.begin(), order.end(), folder);
    INFO(e.path().string());
    REQUIRE(self != order.end());  // every source sits in one of the layers
    ++files;
    std::ifstream in(e.path());
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string text = ss.str();
    for (std::sregex_iterator it(text.begin(), text.end(), inc), end; it != end; ++it) {
      const auto used = std::find(order.begin(), order.end(), (*it)[1].str());
      INFO("includes pipeline/" << (*it)[1].str() << "/");
      REQUIRE(used != order.end());
      CHECK(used <= self);
    }
  }
  CHECK(files > 40);
}
