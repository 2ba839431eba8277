// Reading a test's output files whole.
#pragma once
#include <string>

namespace sgnlf::test {

// The whole contents of a file, bytes as they are ("" when missing).
std::string file_contents(const std::string& path);

}  // namespace sgnlf::test
