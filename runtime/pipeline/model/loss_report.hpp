// The values of a training step's loss terms as the trainer logs them and checks them for
// divergence (issue 67 item 3): one record per named value, each as it enters the objective
// (weighted), in the order of the model's list of terms (loss_term.hpp). A term reports one
// value ("chamfer", "flow") or its parts (the range term's "depth", "return", "intensity").
#pragma once
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace sgnlf::pipeline {

struct LossRecord {
  std::string name;
  double value = 0.0;
  // Summed into total(): false for a term without a lower bound (the adversarial generator
  // loss −mean D(fake)), which would make the divergence tracker's "best" meaningless.
  bool in_total = true;
};

class LossReport {
 public:
  void add(std::string name, double value, bool in_total = true) {
    records_.push_back({std::move(name), value, in_total});
  }
  const std::vector<LossRecord>& records() const { return records_; }
  // The named value; 0 when no term reported it.
  double value(const std::string& name) const {
    for (const auto& r : records_)
      if (r.name == name) return r.value;
    return 0.0;
  }
  bool has(const std::string& name) const {
    for (const auto& r : records_)
      if (r.name == name) return true;
    return false;
  }
  // Σ of the records in the total, in list order and in float: the precision and order the
  // batch loss (depth + return + intensity + grad + carve) was always summed in, which GeoNLF's
  // selective reweighting ranks frames by.
  float total() const {
    bool first = true;
    float t = 0.0f;
    for (const auto& r : records_) {
      if (!r.in_total) continue;
      t = first ? float(r.value) : t + float(r.value);
      first = false;
    }
    return t;
  }
  // Every record finite (the divergence check's NaN test covers the terms out of the total).
  bool finite() const {
    for (const auto& r : records_)
      if (!std::isfinite(r.value)) return false;
    return true;
  }

 private:
  std::vector<LossRecord> records_;
};

}  // namespace sgnlf::pipeline
