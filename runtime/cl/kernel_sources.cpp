#include "cl/kernel_sources.hpp"

#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

#include "core/error.hpp"

namespace sgnlf::cl {
namespace {

void inline_includes(const std::string& path, std::set<std::string>& seen, std::string& out) {
  if (!seen.insert(path).second) return;
  std::istringstream in(kernel_file(path));
  std::string line;
  int lineno = 0;
  out += "#line 1 \"" + path + "\"\n";
  while (std::getline(in, line)) {
    ++lineno;
    const auto first = line.find_first_not_of(" \t");
    if (first != std::string::npos && line.compare(first, 8, "#include") == 0) {
      const auto q0 = line.find('"');
      const auto q1 = q0 == std::string::npos ? q0 : line.find('"', q0 + 1);
      if (q1 == std::string::npos)
        throw Error("kernel " + path + ":" + std::to_string(lineno) +
                    ": only #include \"file\" is supported");
      inline_includes(line.substr(q0 + 1, q1 - q0 - 1), seen, out);
      out += "#line " + std::to_string(lineno + 1) + " \"" + path + "\"\n";
      continue;
    }
    out += line;
    out += '\n';
  }
}

}  // namespace

std::string kernel_file(const std::string& path) {
  if (const char* dir = std::getenv("SGNLF_KERNEL_DIR"); dir && *dir) {
    const std::string full = std::string(dir) + "/" + path;
    std::ifstream f(full, std::ios::binary);
    if (!f) throw Error("kernel file not found: " + full + " (SGNLF_KERNEL_DIR is set)");
    std::ostringstream s;
    s << f.rdbuf();
    return s.str();
  }
  for (const auto& [name, text] : embedded_files())
    if (name == path) return std::string(text);
  throw Error("kernel file '" + path + "' is not embedded in this binary (rebuild after adding it)");
}

std::string kernel_source(const std::string& path) {
  std::set<std::string> seen;
  std::string out;
  inline_includes(path, seen, out);
  return out;
}

}  // namespace sgnlf::cl
