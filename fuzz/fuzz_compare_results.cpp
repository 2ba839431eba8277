// Results JSON read by `sgnlf compare NEW BASELINE` (harness::compare_results). The input is
// the new result (first byte even) or the baseline (odd), compared with the committed smoke
// baseline on the other side, as a user's hand-edited or foreign file would be.
#include <fstream>
#include <iterator>

#include "core/config.hpp"
#include "core/error.hpp"
#include "fuzz_input.hpp"
#include "harness/compare.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const sgnlf::Json baseline = sgnlf::load_json_file(SGNLF_FUZZ_BASELINE);
  if (size == 0) return 0;
  const std::string path = sgnlf::fuzz::write_input("results.json", data + 1, size - 1);
  try {
    const sgnlf::Json j = sgnlf::load_json_file(path);
    const auto rep = data[0] & 1 ? sgnlf::harness::compare_results(baseline, j)
                                 : sgnlf::harness::compare_results(j, baseline);
    (void)sgnlf::harness::format_report(rep);
  } catch (const sgnlf::Error&) {
  }
  return 0;
}
