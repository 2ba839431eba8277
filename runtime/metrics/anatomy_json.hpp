// The error anatomy (anatomy.hpp) as JSON and as the shares a reader looks at first.
// A view's JSON is flat, with fixed keys "<quantity>/<split>/<part>" and numbers or null, so
// that mean_metrics averages views as it averages evaluate_view's (and since every part is a
// linear term of its quantity, the means still add up to the mean quantity):
//   quantity: cd_pred_to_gt, cd_gt_to_pred (m²), depth_mse (m²)
//   <q>/total; <q>/cause/<cause>; <q>/range/<band>; <q>/cause_range/<cause>/<band>;
//   <q>/row/<row, 3 digits>; <q>/train/<band> (null without the training points);
//   pixels/cause_range/<cause>/<band> (share of all pixels); points/pred, points/gt.
// cd_pred_to_gt has the causes both and false, cd_gt_to_pred both and missed, depth_mse all.
#pragma once
#include <string>
#include <vector>

#include "core/config_fwd.hpp"
#include "metrics/anatomy.hpp"

namespace sgnlf::metrics {

// The quantities in key order, and the causes each has.
const std::vector<std::string>& anatomy_quantities();
std::vector<int> anatomy_causes_of(const std::string& quantity);

Json anatomy_json(const ViewAnatomy& a);

// One line of the shares table: a part's share of each quantity, ours and a baseline's
// (NaN where the quantity has no such part or it is undefined); the "total" line holds the
// quantities themselves (m²).
struct AnatomyShareRow {
  std::string split, part;                // "total" / "cause" / "range" / "train", the part
  std::vector<double> model, baseline;    // one per anatomy_quantities()
};

// From two mean anatomy JSONs (anatomy_json, mean_metrics); Error naming the key that a JSON
// lacks. The train rows only when `model` has train distances.
std::vector<AnatomyShareRow> anatomy_shares(const Json& model, const Json& baseline);

}  // namespace sgnlf::metrics
