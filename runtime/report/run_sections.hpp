// The sections of a run's report, each an HTML fragment (<section>…</section>) built from one
// run folder; a missing input is said in the section, not an error.
//   context     method, preset, dataset, seed, step, device, build, the config (collapsible)
//   metrics     model vs naive baseline, mean and per frame; ATE/RPE initial vs optimised
//   curves      loss, learning rate and ATE over the steps (train_log, geometric_log)
//   trajectory  trajectories/top_view.svg (else drawn from the TUM files) and the latest
//               pose-graph picture
//   anatomy     anatomy.json (`sgnlf anatomy`): the errors by cause and band beside the nearest
//               scan's, and its pictures, at most `max_images`; nothing without anatomy.json
//   renders     the PNGs of `sgnlf render` (rendering above the observed scan), embedded
#pragma once
#include <string>

#include "report/run_folder.hpp"

namespace sgnlf::report {

std::string context_section(const RunFolder& run);
std::string metrics_section(const RunFolder& run);
std::string curves_section(const RunFolder& run);
std::string trajectory_section(const RunFolder& run);
std::string anatomy_section(const RunFolder& run, int max_images);
// `renders_dir` empty: none given and RUN/renders absent. At most `max_images` pictures.
std::string renders_section(const RunFolder& run, const std::string& renders_dir,
                            int max_images);

// A metric's table header ("depth PSNR (dB) ↑") and value with the results tables' digits.
std::string metric_header(const std::string& key);
std::string metric_value(const std::string& key, const Json& v);

}  // namespace sgnlf::report
