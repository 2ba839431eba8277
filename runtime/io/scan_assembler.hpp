// Gathers a PCD or PLY scan record by record, the way the KITTI reader treats its records:
// points with a NaN/Inf coordinate, intensity, ring or time (or a value beyond float) are
// dropped and counted, ring and time stay in step with the kept points, the largest intensity
// is tracked, and a scan without any finite point is refused.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "io/scan_fields.hpp"
#include "io/scan_io.hpp"

namespace sgnlf::io {

class ScanAssembler {
 public:
  // `field_of_role`: which roles the file has (-1: absent); `reserve`: points to reserve room
  // for, already bounded by what the file can hold.
  ScanAssembler(std::string path, size_t records, size_t reserve,
                const std::array<int, kFieldRoles>& field_of_role, ScanExtras* extras);
  // One record's values by role (absent roles ignored); `offset`: the record's byte offset.
  void add(const std::array<double, kFieldRoles>& v, size_t offset);
  // Checks that every declared record came, logs the dropped ones, fills stats and extras.
  std::vector<PointXYZI> finish(ScanReadStats* stats);

 private:
  std::string path_;
  size_t records_, added_ = 0, first_offset_ = 0;
  bool has_[kFieldRoles];
  ScanExtras* extras_;
  ScanReadStats st_;
  std::vector<PointXYZI> pts_;
  std::vector<int32_t> ring_;
  std::vector<double> time_;
};

}  // namespace sgnlf::io
