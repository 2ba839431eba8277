// PLY scans (ascii, binary little/big endian, other elements and list properties skipped):
// io::read_ply through read_scan, under the contract of scan_contract.hpp, round-tripped through
// the big-endian writer.
#include "io/ply_reader.hpp"
#include "scan_contract.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace sgnlf;
  return fuzz::check_scan_contract(
      "scan.ply", data, size,
      [](const std::string& p, const std::vector<PointXYZI>& pts, const io::ScanExtras* ex) {
        io::write_ply(p, pts, io::PlyEncoding::kBinaryBigEndian, ex);
      },
      [](const std::string& p, io::ScanExtras* ex) { return io::read_ply(p, nullptr, ex); });
}
