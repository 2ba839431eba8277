// file_contents (see files.hpp).
#include "support/files.hpp"

#include <fstream>
#include <iterator>

namespace sgnlf::test {

std::string file_contents(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

}  // namespace sgnlf::test
