#include "io/scan_assembler.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/log.hpp"

namespace sgnlf::io {
namespace {
// A double that converts to a finite float (a larger one would be undefined behaviour).
bool fits_float(double v) { return std::isfinite(v) && std::fabs(v) <= double(FLT_MAX); }
}  // namespace

ScanAssembler::ScanAssembler(std::string path, size_t records, size_t reserve,
                             const std::array<int, kFieldRoles>& field_of_role, ScanExtras* extras)
    : path_(std::move(path)), records_(records), extras_(extras) {
  for (size_t r = 0; r < kFieldRoles; ++r) has_[r] = field_of_role[r] >= 0;
  st_.records = records;
  const size_t n = std::min(records, reserve);
  pts_.reserve(n);
  if (extras_ && has_[size_t(FieldRole::kRing)]) ring_.reserve(n);
  if (extras_ && has_[size_t(FieldRole::kTime)]) time_.reserve(n);
}

void ScanAssembler::add(const std::array<double, kFieldRoles>& v, size_t offset) {
  const size_t index = added_++;
  const bool has_i = has_[size_t(FieldRole::kIntensity)], has_r = has_[size_t(FieldRole::kRing)],
             has_t = has_[size_t(FieldRole::kTime)];
  const double ring = has_r ? v[size_t(FieldRole::kRing)] : 0.0;
  if (has_r && std::isfinite(ring) && std::fabs(ring) >= 2147483648.0)
    throw IoError(path_ + ": byte offset " + std::to_string(offset) + ": ring " + std::to_string(ring) +
                  " of point " + std::to_string(index) + " is outside int32");
  const bool finite = fits_float(v[0]) && fits_float(v[1]) && fits_float(v[2]) &&
                      (!has_i || fits_float(v[size_t(FieldRole::kIntensity)])) && std::isfinite(ring) &&
                      (!has_t || std::isfinite(v[size_t(FieldRole::kTime)]));
  if (!finite) {
    if (st_.non_finite++ == 0) {
      st_.first_non_finite = index;
      first_offset_ = offset;
    }
    return;
  }
  const float intensity = has_i ? float(v[size_t(FieldRole::kIntensity)]) : 0.f;
  if (pts_.empty() || intensity > st_.max_intensity) st_.max_intensity = intensity;
  pts_.push_back({float(v[0]), float(v[1]), float(v[2]), intensity});
  if (extras_ && has_r) ring_.push_back(int32_t(std::lround(ring)));
  if (extras_ && has_t) time_.push_back(v[size_t(FieldRole::kTime)]);
}

std::vector<PointXYZI> ScanAssembler::finish(ScanReadStats* stats) {
  if (added_ != records_)
    throw IoError(path_ + ": " + std::to_string(added_) + " of " + std::to_string(records_) + " points read");
  if (st_.non_finite > 0)
    log::warn(path_, ": dropped ", st_.non_finite, " of ", records_, " points with NaN/Inf values (first: point ",
              st_.first_non_finite, " at byte offset ", first_offset_, ")");
  if (pts_.empty())
    throw IoError(path_ + ": empty scan (no finite point among " + std::to_string(records_) + ")");
  if (!has_[size_t(FieldRole::kIntensity)]) st_.max_intensity = 0.f;
  if (stats) *stats = st_;
  if (extras_) {
    extras_->ring = std::move(ring_);
    extras_->time = std::move(time_);
    extras_->has_intensity = has_[size_t(FieldRole::kIntensity)];
    extras_->has_ring = has_[size_t(FieldRole::kRing)];
    extras_->has_time = has_[size_t(FieldRole::kTime)];
  }
  return std::move(pts_);
}

}  // namespace sgnlf::io
