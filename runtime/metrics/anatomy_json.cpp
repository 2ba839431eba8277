// anatomy_json / anatomy_shares (see anatomy_json.hpp).
#include "metrics/anatomy_json.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

#include "core/config.hpp"
#include "core/error.hpp"

namespace sgnlf::metrics {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

Json number_or_null(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

void put_split(Json& j, const std::string& q, const ErrorSplit& s) {
  const auto& causes = anatomy_cause_names();
  const auto& bands = anatomy_range_band_names();
  j[q + "/total"] = number_or_null(s.total);
  for (int c : anatomy_causes_of(q)) {
    j[q + "/cause/" + causes[size_t(c)]] = number_or_null(s.cause(c));
    for (int b = 0; b < kAnatomyRangeBands; ++b)
      j[q + "/cause_range/" + causes[size_t(c)] + "/" + bands[size_t(b)]] =
          number_or_null(s.by_cause_range[size_t(c)][size_t(b)]);
  }
  for (int b = 0; b < kAnatomyRangeBands; ++b)
    j[q + "/range/" + bands[size_t(b)]] = number_or_null(s.band(b));
  for (size_t r = 0; r < s.by_row.size(); ++r) {
    char row[24];
    std::snprintf(row, sizeof row, "%03zu", r);
    j[q + "/row/" + row] = number_or_null(s.by_row[r]);
  }
  for (int b = 0; b < kAnatomyTrainBands; ++b)
    j[q + "/train/" + anatomy_train_band_names()[size_t(b)]] = number_or_null(s.by_train[size_t(b)]);
}

double number_at(const Json& j, const std::string& key, const char* which) {
  require(j.is_object() && j.contains(key),
          std::string("anatomy_shares: the ") + which + " anatomy has no key '" + key + "'");
  const Json& v = j.at(key);
  require(v.is_null() || v.is_number(), std::string("anatomy_shares: the ") + which +
                                            " anatomy's '" + key + "' is " + v.dump());
  return v.is_number() ? v.get<double>() : kNaN;
}

}  // namespace

const std::vector<std::string>& anatomy_quantities() {
  static const std::vector<std::string> q = {"cd_pred_to_gt", "cd_gt_to_pred", "depth_mse"};
  return q;
}

std::vector<int> anatomy_causes_of(const std::string& quantity) {
  if (quantity == "cd_pred_to_gt") return {kCauseBoth, kCauseFalse};
  if (quantity == "cd_gt_to_pred") return {kCauseBoth, kCauseMissed};
  if (quantity == "depth_mse") return {kCauseBoth, kCauseMissed, kCauseFalse};
  throw Error("anatomy: unknown quantity '" + quantity + "'");
}

Json anatomy_json(const ViewAnatomy& a) {
  Json j = Json::object();
  put_split(j, "cd_pred_to_gt", a.cd_pred_to_gt);
  put_split(j, "cd_gt_to_pred", a.cd_gt_to_pred);
  put_split(j, "depth_mse", a.depth_mse);
  for (int c = 0; c < kAnatomyCauses; ++c)
    for (int b = 0; b < kAnatomyRangeBands; ++b)
      j["pixels/cause_range/" + anatomy_cause_names()[size_t(c)] + "/" +
        anatomy_range_band_names()[size_t(b)]] = a.pixels[size_t(c)][size_t(b)];
  j["points/pred"] = a.n_pred;
  j["points/gt"] = a.n_gt;
  return j;
}

std::vector<AnatomyShareRow> anatomy_shares(const Json& model, const Json& baseline) {
  const auto& qs = anatomy_quantities();
  std::vector<AnatomyShareRow> rows;
  auto row = [&](const std::string& split, const std::string& part) {
    AnatomyShareRow r{split, part, {}, {}};
    for (const auto& q : qs) {
      const auto one = [&](const Json& j, const char* which) {
        const double total = number_at(j, q + "/total", which);
        if (split == "total") return total;
        const std::string key = q + "/" + split + "/" + part;
        if (!j.contains(key)) return kNaN;  // a cause this quantity does not have
        return number_at(j, key, which) / total;
      };
      r.model.push_back(one(model, "model"));
      r.baseline.push_back(one(baseline, "baseline"));
    }
    rows.push_back(std::move(r));
  };
  row("total", "");
  for (const auto& c : anatomy_cause_names()) row("cause", c);
  for (const auto& b : anatomy_range_band_names()) row("range", b);
  if (std::isfinite(number_at(model, "depth_mse/train/" + anatomy_train_band_names()[0], "model")))
    for (const auto& b : anatomy_train_band_names()) row("train", b);
  return rows;
}

}  // namespace sgnlf::metrics
