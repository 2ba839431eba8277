// The fast renderer's command-line options, shared by `sgnlf render` and `sgnlf eval`:
// --renderer fast|protocol, --fast-layout protocol|march, --fast-config FILE (JSON of
// render::FastRenderConfig over the layout's settings), --cell M.
#pragma once
#include <memory>
#include <string>

#include "apps/command.hpp"
#include "pipeline/model/fast_renderer.hpp"
#include "pipeline/run/session.hpp"
#include "render/fast_render_config.hpp"

namespace sgnlf::app {

struct FastRenderOptions {
  std::string renderer, config_file, layout = "protocol";
  float cell_m = 0.0f;

  void add(CLI::App& sub, const std::string& default_renderer, const std::string& what) {
    renderer = default_renderer;
    sub.add_option("--renderer", renderer,
                   "fast (occupancy grid, early termination, the head where the weight matters) "
                   "or protocol (every sample, as the tables are rendered); default " +
                       default_renderer + what)
        ->check(CLI::IsMember({"fast", "protocol"}));
    sub.add_option("--fast-layout", layout,
                   "Where the fast renderer's samples are: protocol (the protocol's samples, those "
                   "in empty cells skipped: every metric within 0.02 dB of the protocol's render) "
                   "or march (placed by the grid, no importance pass: 3x faster on an opaque "
                   "SG-NLF field, metrics within 1 %; docs/studies/fast-render). Default protocol")
        ->check(CLI::IsMember({"protocol", "march"}));
    sub.add_option("--fast-config", config_file,
                   "JSON of the fast renderer's settings over those of --fast-layout (keys of "
                   "render/fast_render_config.hpp)");
    sub.add_option("--cell", cell_m, "Occupancy grid cell of the fast renderer, metres (default 1)");
  }
  // The settings (validated; a bad file or value throws naming it), read before the run loads.
  render::FastRenderConfig config() const {
    render::FastRenderConfig c =
        layout == "march" ? render::FastRenderConfig::march() : render::FastRenderConfig{};
    if (!config_file.empty())
      c = render::FastRenderConfig::from_json(load_config_file(config_file), config_file, c);
    if (cell_m > 0.0f) c.cell_m = cell_m;
    c.validate("--cell");
    return c;
  }
  // The fast renderer of a loaded run, or null for the protocol's.
  std::unique_ptr<pipeline::FastRenderer> make(cl::Runtime& rt, pipeline::LoadedRun& run,
                                               const render::FastRenderConfig& c) const {
    if (renderer != "fast") return nullptr;
    return std::make_unique<pipeline::FastRenderer>(rt, *run.model, *run.scene, c,
                                                    run.manifest.config.schedule.render_chunk_rays);
  }
};

}  // namespace sgnlf::app
