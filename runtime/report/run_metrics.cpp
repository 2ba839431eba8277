// The metrics section of a run's report (run_sections.hpp): metrics.json's means and per-frame
// values beside the naive baseline's (the nearest training scan, protocol §4), and the poses'
// ATE/RPE before and after optimisation (from reconstruct.json in a `sgnlf reconstruct` folder).
#include <algorithm>
#include <cmath>

#include "core/config.hpp"
#include "core/json_lookup.hpp"
#include "harness/markdown.hpp"
#include "harness/tables.hpp"
#include "report/html.hpp"
#include "report/run_sections.hpp"

namespace sgnlf::report {
namespace {

// Null for a missing key or a non-object (core/json_lookup.hpp): never throws.
constexpr auto at = &member_or_null;

// Table order; keys a metrics file has beyond these follow them.
const std::vector<std::string> kOrder = {
    "cd", "fscore", "depth_rmse", "depth_psnr", "depth_ssim", "depth_delta1", "depth_medae",
    "intensity_psnr", "intensity_ssim", "intensity_rmse", "intensity_medae", "raydrop_f1",
    "raydrop_acc", "raydrop_rmse", "cd_pred_to_gt", "cd_gt_to_pred"};
// The per-frame table's columns: the paper's, then ray drop.
const std::vector<std::string> kPerFrame = {"cd", "fscore", "depth_rmse", "depth_psnr",
                                            "intensity_psnr", "raydrop_f1"};
const std::vector<std::string> kPose = {"ate_m", "ate_h_m", "rpe_t_cm", "rpe_r_deg"};

std::vector<std::string> metric_keys(const Json& m) {
  std::vector<std::string> keys;
  for (const auto& k : kOrder)
    if (m.contains(k)) keys.push_back(k);
  for (const auto& [k, v] : m.items())
    if (std::find(kOrder.begin(), kOrder.end(), k) == kOrder.end() && v.is_number())
      keys.push_back(k);
  return keys;
}

// "better" / "worse" class of `a` against `b` for a metric (none when either is not a number).
std::string compare_class(const std::string& key, const Json& a, const Json& b) {
  if (!a.is_number() || !b.is_number() || a.get<double>() == b.get<double>()) return "";
  const harness::MetricInfo* m = harness::metric_info(key);
  if (m && !m->judged()) return "";  // a diagnostic: neither better nor worse
  const bool lower = m ? m->lower_better : true;
  return (a.get<double>() < b.get<double>()) == lower ? " class=\"better\"" : " class=\"worse\"";
}

std::string cell(const std::string& key, const Json& v, const Json& other) {
  return "<span" + compare_class(key, v, other) + ">" + escape(metric_value(key, v)) + "</span>";
}

// Means: model (and the fast renderer's, when scored) against the naive baseline.
std::string mean_table(const Json& model, const Json& fast, const Json& naive) {
  std::vector<std::vector<std::string>> rows;
  for (const auto& k : metric_keys(model)) {
    const Json &a = at(model, k), &b = at(naive, k);
    std::string diff = "—";
    if (a.is_number() && b.is_number())
      diff = escape(metric_value(k, a.get<double>() - b.get<double>()));
    std::vector<std::string> row = {escape(metric_header(k)), cell(k, a, b)};
    if (fast.is_object()) row.push_back(cell(k, at(fast, k), b));
    row.push_back(escape(metric_value(k, b)));
    row.push_back(diff);
    rows.push_back(std::move(row));
  }
  std::vector<std::string> head = {"metric", "model"};
  if (fast.is_object()) head.push_back("model, fast renderer");
  head.insert(head.end(), {"naive baseline", "model − naive"});
  return html_table(head, rows, "num");
}

std::string per_frame_table(const Json& frames, const Json& naive_frames) {
  std::vector<std::string> head = {"frame"};
  for (const auto& k : kPerFrame) head.push_back(escape(metric_header(k)));
  std::vector<std::vector<std::string>> rows;
  for (size_t i = 0; i < frames.size(); ++i) {
    const Json& f = frames[i];
    const Json& n = naive_frames.is_array() && i < naive_frames.size() ? naive_frames[i] : Json();
    std::vector<std::string> row = {escape(f.contains("frame") ? f["frame"].dump() : "—")};
    for (const auto& k : kPerFrame)
      row.push_back(cell(k, at(f, k), at(n, k)) + "<br><small>naive " +
                    escape(metric_value(k, at(n, k))) + "</small>");
    rows.push_back(std::move(row));
  }
  return html_table(head, rows, "num");
}

// The ATE the reference poses support (pose_metrics.ate_reference: "horizontal" when every
// ground-truth z is equal, as nuScenes' ego poses; "3d" otherwise); "" when not recorded.
std::string supported_ate(const Json& pose) {
  const Json& r = at(pose, "ate_reference");
  if (r == Json("horizontal")) return "ate_h_m";
  if (r == Json("3d")) return "ate_m";
  return "";
}

std::string pose_table(const Json& initial, const Json& optimised,
                       const std::string& initial_name = "initial poses") {
  const std::string supported = supported_ate(optimised);
  std::vector<std::vector<std::string>> rows;
  for (const auto& k : kPose)
    rows.push_back({escape(metric_header(k)) +
                        (k == supported ? "<br><small>the one the reference supports</small>" : ""),
                    escape(metric_value(k, at(initial, k))),
                    cell(k, at(optimised, k), at(initial, k))});
  std::string o;
  if (supported == "ate_h_m")
    o = "<p>The reference poses are planar (every z equal, as nuScenes' ego poses): they support "
        "the horizontal ATE (x, y under the same 3D alignment), not the 3D one.</p>\n";
  else if (supported == "ate_m")
    o = "<p>The reference poses vary in z: they support the 3D ATE; the horizontal one (x, y "
        "under the same alignment) is beside it.</p>\n";
  return o + html_table({"pose metric", initial_name, "optimised poses"}, rows, "num");
}

std::string scored(const Json& m, const Json& fast, const std::string& file) {
  const Json& naive = at(m, "naive_baseline");
  std::string o = "<p>Mean over the test frames (" + escape(file);
  if (fast.is_object()) o += "; the fast renderer's from metrics-fast.json";
  o += "). Naive baseline: the nearest training scan moved to the test pose (protocol §4). "
       "Green: better than the naive baseline.</p>\n";
  o += mean_table(at(m, "metrics"), at(fast, "metrics"), at(naive, "metrics"));
  if (at(m, "per_frame").is_array() && !m["per_frame"].empty())
    o += "<h3>Per frame</h3>\n" + per_frame_table(m["per_frame"], at(naive, "per_frame"));
  return o;
}

}  // namespace

std::string metric_header(const std::string& key) {
  const harness::MetricInfo* m = harness::metric_info(key);
  if (!m) return key;
  return m->label + (m->unit.empty() ? "" : " (" + m->unit + ")") + m->arrow();
}

std::string metric_value(const std::string& key, const Json& v) {
  return harness::format_metric(key, v);
}

std::string metrics_section(const RunFolder& r) {
  std::string o = "<section><h2>Metrics</h2>\n";
  if (r.metrics.is_object()) {
    o += scored(r.metrics, r.metrics_fast, "metrics.json");
  } else if (r.metrics_fast.is_object()) {
    o += scored(r.metrics_fast, Json(), "metrics-fast.json, fast renderer");
  } else {
    o += "<p class=\"note\">No metrics.json: <code>sgnlf eval " + escape(r.path) +
         "</code> scores the test views.</p>\n";
  }
  const Json& src = r.metrics.is_object() ? r.metrics : r.summary;
  if (at(src, "pose_metrics").is_object())
    o += "<h3>Poses</h3>\n<p>After Umeyama alignment on the positions (protocol §4).</p>\n" +
         pose_table(at(src, "initial_pose_metrics"), src["pose_metrics"]);
  else if (r.reconstruct.is_object()) {
    // A `sgnlf reconstruct` folder: its scans have no reference poses in their layout; the
    // record holds ATE/RPE only when --reference-poses scored them.
    const Json& pe = at(r.reconstruct, "pose_errors");
    o += "<h3>Poses</h3>\n";
    if (pe.is_object())
      o += "<p>Against the reference poses given to <code>sgnlf reconstruct "
           "--reference-poses</code>, after Umeyama alignment on the positions (protocol "
           "§4); reconstruct.json.</p>\n" +
           pose_table(at(pe, "odometry"), at(pe, "optimised"), "odometry poses");
    else
      o += "<p class=\"note\">No reference poses, so no ATE: <code>sgnlf reconstruct "
           "--reference-poses FILE</code> on this folder scores the odometry and the optimised "
           "poses.</p>\n";
  }
  return o + "</section>\n";
}

}  // namespace sgnlf::report
