// Kernel sources: embedded into the binary at build time (cmake/embed_kernels_script.cmake),
// or read from $SGNLF_KERNEL_DIR while developing. `#include "path"` lines naming another
// kernel file are inlined here, so programs build without include paths on any device.
#pragma once
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace sgnlf::cl {

// Path relative to kernels/ → file text, for every embedded .cl/.clh file.
const std::vector<std::pair<std::string_view, std::string_view>>& embedded_files();

// The raw text of one kernel file (embedded, or from SGNLF_KERNEL_DIR when set).
std::string kernel_file(const std::string& path);

// The text with its #include "..." lines resolved (each file inlined once).
std::string kernel_source(const std::string& path);

}  // namespace sgnlf::cl
