// The context section of a run's report (run_sections.hpp).
#include <cstdio>
#include <string>

#include "core/config.hpp"
#include "core/json_lookup.hpp"
#include "report/html.hpp"
#include "report/run_sections.hpp"

namespace sgnlf::report {
namespace {

// Null for a missing key or a non-object (core/json_lookup.hpp): never throws.
constexpr auto at = &member_or_null;

std::string text_of(const Json& v) {
  if (v.is_null()) return "—";
  if (v.is_string()) return v.get<std::string>().empty() ? "—" : v.get<std::string>();
  if (v.is_number_float()) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v.get<double>());
    return buf;
  }
  return v.dump();
}

// The first non-empty of the candidates.
const Json& first_of(std::initializer_list<const Json*> v) {
  static const Json null_json;
  for (const Json* j : v)
    if (!j->is_null() && !(j->is_string() && j->get<std::string>().empty())) return *j;
  return null_json;
}

// Build and git facts of a run-context block (harness/context.hpp), when the run recorded one.
void build_rows(const Json& ctx, std::vector<std::vector<std::string>>& rows) {
  const Json& git = at(ctx, "git");
  if (!git.is_null())
    rows.push_back({"git", escape(text_of(at(git, "sha")) +
                                  (at(git, "dirty") == Json(true) ? " (dirty)" : ""))});
  const Json& b = at(ctx, "build");
  if (!b.is_null())
    rows.push_back({"build", escape(text_of(at(b, "build_type")) + ", " +
                                    text_of(at(b, "compiler")) + " " +
                                    text_of(at(b, "compiler_version")))});
  const Json& cl = at(ctx, "opencl");
  if (!cl.is_null())
    rows.push_back({"OpenCL", escape(text_of(at(cl, "platform")) + " / " +
                                     text_of(at(cl, "device")))});
}

}  // namespace

std::string context_section(const RunFolder& r) {
  const Json &run = r.run, &sum = r.summary, &met = r.metrics;
  std::vector<std::vector<std::string>> rows;
  auto add = [&](const std::string& k, const Json& v) { rows.push_back({escape(k), escape(text_of(v))}); };
  add("method", at(run, "method"));
  add("preset", at(run, "preset"));
  add("dataset", first_of({&at(met, "dataset"), &at(run, "dataset")}));
  add("dataset path", at(run, "dataset"));
  add("seed", at(run, "seed"));
  add("step", first_of({&at(met, "step"), &at(sum, "end_step")}));
  add("device", first_of({&at(run, "device"), &at(sum, "device")}));
  add("config hash", at(run, "config_hash"));
  add("pose initialisation", first_of({&at(met, "pose_init"), &at(at(run, "config"), "poses")}));
  if (!sum.is_null()) {
    add("frames (train / test)", Json(text_of(at(sum, "train_frames")) + " / " +
                                      text_of(at(sum, "test_frames"))));
    add("training time (s)", at(sum, "train_seconds"));
    add("steps per second", at(sum, "steps_per_s"));
    add("parameters", at(sum, "parameters"));
    add("finished", at(sum, "finished"));
  }
  const Json& ctx = first_of({&at(run, "context"), &at(sum, "context")});
  if (ctx.is_object()) build_rows(ctx, rows);
  else rows.push_back({"build", "<span class=\"note\">not recorded in the run folder</span>"});

  std::string o = "<section><h2>Run</h2>\n" + html_table({"", ""}, rows, "kv");
  if (at(run, "config").is_object()) o += json_details("resolved config (run.json)", run["config"]);
  if (ctx.is_object()) o += json_details("run context", ctx);
  return o + "</section>\n";
}

}  // namespace sgnlf::report
