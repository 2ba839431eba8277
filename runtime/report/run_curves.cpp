// The training-curves section of a run's report (run_sections.hpp): train_log.jsonl's losses
// (log axis), learning rate and, for the pose-free methods, ATE over the steps, with the
// geometric stage's ATE after each of its steps (geometric_log.jsonl) beside it.
#include <map>

#include "core/config.hpp"
#include "report/html.hpp"
#include "report/run_sections.hpp"
#include "report/svg_chart.hpp"

namespace sgnlf::report {
namespace {

const char* const kColours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728",
                                "#9467bd", "#8c564b", "#e377c2", "#7f7f7f"};

double number_or_nan(const Json& j) { return j.is_number() ? j.get<double>() : NAN; }

// Series by name, in order of first appearance.
struct SeriesSet {
  std::vector<ChartSeries> list;
  void add(const std::string& name, double x, double y) {
    for (auto& s : list)
      if (s.name == name) {
        s.x.push_back(x), s.y.push_back(y);
        return;
      }
    list.push_back({name, kColours[list.size() % 8], {x}, {y}});
  }
};

}  // namespace

std::string curves_section(const RunFolder& r) {
  const auto log = read_json_lines(r.file("train_log.jsonl"));
  const auto geo = read_json_lines(r.file("geometric_log.jsonl"));
  std::string o = "<section><h2>Training curves</h2>\n";
  if (log.empty()) return o + "<p class=\"note\">No train_log.jsonl in the run folder.</p></section>\n";

  SeriesSet loss, lr, ate;
  for (const auto& e : log) {
    if (!e.is_object() || !e.contains("step")) continue;
    const double step = number_or_nan(e["step"]);
    const Json& l = e.value("loss", Json());
    if (l.is_object()) {
      if (l.contains("total")) loss.add("total", step, number_or_nan(l["total"]));
      for (const auto& [k, v] : l.items())
        if (k != "total") loss.add(k, step, number_or_nan(v));
    } else if (l.is_number()) {
      loss.add("loss", step, l.get<double>());
    }
    if (e.contains("lr")) lr.add("field lr", step, number_or_nan(e["lr"]));
    if (e.contains("pose") && e["pose"].is_object() && e["pose"].contains("ate_m"))
      ate.add("ATE (training log)", step, number_or_nan(e["pose"]["ate_m"]));
    if (e.contains("pose") && e["pose"].is_object() && e["pose"].contains("ate_h_m"))
      ate.add("horizontal ATE (training log)", step, number_or_nan(e["pose"]["ate_h_m"]));
  }
  for (const auto& g : geo)
    if (g.is_object() && g.contains("step") && g.contains("after") && g["after"].is_object())
      ate.add("ATE after geometric step", number_or_nan(g["step"]),
              number_or_nan(g["after"].value("ate_m", Json())));
  for (auto& s : ate.list) s.dots = s.x.size() < 80;

  o += "<p>" + std::to_string(log.size()) + " entries of train_log.jsonl";
  if (!geo.empty()) o += ", " + std::to_string(geo.size()) + " of geometric_log.jsonl";
  o += ".</p>\n<div class=\"charts\">\n";
  o += svg_chart(loss.list, {"Loss (per term; zero terms are not drawn on the log axis)", "step",
                             "loss", true});
  o += svg_chart(lr.list, {"Learning rate", "step", "lr", true});
  if (!ate.list.empty()) o += svg_chart(ate.list, {"ATE over the steps", "step", "ATE (m)", true});
  return o + "</div></section>\n";
}

}  // namespace sgnlf::report
