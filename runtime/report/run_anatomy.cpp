// The error-anatomy section of a run's report (run_sections.hpp): anatomy.json's shares of each
// CD direction and of the depth MSE by cause, range band and distance to the training scans,
// ours beside the nearest training scan's, and the anatomy pictures (docs/anatomy.md).
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/config.hpp"
#include "core/json_lookup.hpp"
#include "metrics/anatomy_json.hpp"
#include "report/html.hpp"
#include "report/run_sections.hpp"

namespace sgnlf::report {
namespace fs = std::filesystem;
namespace {

constexpr auto at = &member_or_null;

std::string cell(double v, bool share) {
  if (!std::isfinite(v)) return "—";
  char buf[32];
  std::snprintf(buf, sizeof buf, share ? "%.1f %%" : "%.4g", share ? 100.0 * v : v);
  return buf;
}

std::string shares_table(const Json& a) {
  const auto rows = metrics::anatomy_shares(at(at(a, "model"), "mean"),
                                            at(at(a, "naive_baseline"), "mean"));
  const std::vector<std::string> head = {"split", "part", "CD pred→GT, ours", "nearest scan",
                                         "CD GT→pred, ours", "nearest scan", "depth MSE, ours",
                                         "nearest scan"};
  std::vector<std::vector<std::string>> body;
  for (const auto& r : rows) {
    const bool share = r.split != "total";
    std::vector<std::string> row = {escape(share ? r.split : "total (m²)"), escape(r.part)};
    for (size_t q = 0; q < r.model.size(); ++q) {
      row.push_back(escape(cell(r.model[q], share)));
      row.push_back(escape(cell(r.baseline[q], share)));
    }
    body.push_back(std::move(row));
  }
  return html_table(head, body, "num");
}

}  // namespace

std::string anatomy_section(const RunFolder& r, int max_images) {
  // Only where `sgnlf anatomy` (or reconstruct) wrote it: a bench page's many runs stay quiet.
  if (!r.anatomy.is_object()) return "";
  std::string o = "<section><h2>Error anatomy</h2>\n";
  o += "<p>Where the mean CD (each direction) and depth MSE of the test views come from "
       "(anatomy.json; docs/anatomy.md): the total, then each part's share of it, ours beside "
       "the nearest training scan's. Causes: <b>both</b> = range error where the prediction and "
       "the sensor return, <b>missed</b> = the sensor returned and the prediction did not, "
       "<b>false</b> = the prediction returned where the sensor did not. Range bands by the "
       "observed range (a false return's by the predicted one); train = distance to the nearest "
       "point of any training scan.</p>\n";
  try {
    o += shares_table(r.anatomy);
  } catch (const std::exception& e) {
    o += "<p class=\"note\">anatomy.json cannot be read: " + escape(e.what()) + "</p>\n";
  }
  const Json& frames = at(at(r.anatomy, "model"), "per_frame");
  int shown = 0;
  std::string figs;
  for (const auto& f : frames.is_array() ? frames : Json::array()) {
    const std::string id = at(f, "frame").dump();
    const std::string png = r.file("anatomy/" + id + ".png");
    if (!fs::exists(png)) continue;
    if (shown++ == max_images) break;
    figs += "<figure>" + embedded_img(png, "image/png", "anatomy of frame " + id) +
            "<figcaption>frame " + escape(id) + ": ours, the nearest scan, the observed scan "
            "(anatomy/" + escape(id) + ".png)</figcaption></figure>\n";
  }
  if (!figs.empty())
    o += "<p>Each picture, top to bottom: our rendering, the nearest scan's, the observed scan "
         "(depth in turbo); magenta: a false return, white: a missed return.</p>\n<div class=\"renders\">\n" + figs +
         "</div>\n";
  return o + "</section>\n";
}

}  // namespace sgnlf::report
