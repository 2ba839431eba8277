// PCD scans (ascii, binary, binary_compressed with LZF): io::read_pcd through read_scan, under
// the contract of scan_contract.hpp, round-tripped through the binary_compressed writer (the
// LZF compressor).
#include "io/pcd_reader.hpp"
#include "scan_contract.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace sgnlf;
  return fuzz::check_scan_contract(
      "scan.pcd", data, size,
      [](const std::string& p, const std::vector<PointXYZI>& pts, const io::ScanExtras* ex) {
        io::write_pcd(p, pts, io::PcdEncoding::kBinaryCompressed, ex);
      },
      [](const std::string& p, io::ScanExtras* ex) { return io::read_pcd(p, nullptr, ex); });
}
