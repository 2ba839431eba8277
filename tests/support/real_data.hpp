// Where the real-data tests find their scans. The large excerpts live outside the repository in
// $SGNLF_SHARED_DIR/data/real (else ../shared/data/real beside the checkout); a small genuine
// sample of each (datasets/real-sample/: the same folder names and layouts, fewer frames, scans
// byte for byte) is committed, so the real-data tests also run on a fresh clone anywhere.
// Under CI=true or SGNLF_REQUIRE_REAL_DATA=1 (.ci/run sets it) the large data is required: a test
// that asks for it fails when it is missing instead of shrinking to the sample.
#pragma once
#include <string>

namespace sgnlf::test {

struct RealData {
  std::string path;   // folder or file to read; empty: the test is to return (a warning was given)
  bool full = false;  // true: the large data; false: the in-repo sample
  explicit operator bool() const { return !path.empty(); }
};

bool real_data_required();       // CI=true or SGNLF_REQUIRE_REAL_DATA=1
std::string real_data_root();    // shared_dir() + "/data/real"
std::string real_sample_root();  // source_dir() + "/datasets/real-sample"

// `name` is relative to data/real (e.g. "kitti-odometry-00-slice"): the large data when present,
// else (not required) the in-repo sample, with a warning naming both; neither: a warning, empty.
RealData real_data(const std::string& name);
// For a test that needs more than the sample holds: the large data, else (not required) a warning
// saying why (`needs`, e.g. "the protocol's 36 keyframes; the in-repo sample holds 2") and an
// empty path.
RealData full_real_data(const std::string& name, const std::string& needs);

}  // namespace sgnlf::test
