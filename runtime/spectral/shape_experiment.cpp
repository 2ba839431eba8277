// Shape experiment: training, readout, group comparison, JSON and Markdown (shape_experiment.hpp).
#include "spectral/shape_experiment.hpp"

#include <chrono>
#include <cstdio>

#include "core/config.hpp"

namespace sgnlf::spectral {

ShapeExperimentResult run_shape_experiment(SpectralTrainer& trainer, const ShapeSpec& spec, size_t eval_points,
                                           const std::function<void(int, double)>& on_step) {
  ShapeExperimentResult r;
  r.spec = spec;
  r.config = trainer.config();
  const auto shape = make_shape(spec);
  const int k = trainer.config().psi.k;
  {
    Rng rng(trainer.config().seed, 7);
    const auto pts = shape->sample(rng, 400000);
    std::vector<double> prob;
    r.sampler_uniformity = cell_uniformity(chart_cells(*shape, spec, pts, 32, 16, prob), prob);
  }
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  r.train = trainer.train([&](Rng& rng, size_t n) { return shape->sample(rng, n); }, on_step);
  const auto t1 = clock::now();
  const auto lattice = shape->lattice(eval_points);
  r.eval_points = lattice.size();
  const auto ritz = trainer.readout(lattice, true);
  r.readout_seconds = std::chrono::duration<double>(clock::now() - t1).count();
  r.train_seconds = std::chrono::duration<double>(t1 - t0).count();
  r.learned = ritz.eigenvalues;
  r.analytic = shape->spectrum(k);
  r.groups = compare_groups(r.learned, r.analytic);
  for (const auto& g : r.groups) r.max_group_rel_err = std::max(r.max_group_rel_err, g.rel_err);
  return r;
}

std::vector<float> chart_maps(SpectralTrainer& trainer, const Shape& shape, int n_funcs, int tile_w, int tile_h) {
  std::vector<Eigen::Vector3d> x;
  x.reserve(size_t(tile_w) * tile_h);
  for (int j = 0; j < tile_h; ++j)
    for (int i = 0; i < tile_w; ++i) x.push_back(shape.at_chart((i + 0.5) / tile_w, (j + 0.5) / tile_h).x);
  const auto y = trainer.evaluate(x);
  const int k = trainer.config().psi.k;
  n_funcs = std::min(n_funcs, k);
  std::vector<float> maps(size_t(n_funcs) * x.size());
  for (int f = 0; f < n_funcs; ++f)
    for (size_t p = 0; p < x.size(); ++p) maps[size_t(f) * x.size() + p] = y[p * k + f];
  return maps;
}

Json ShapeExperimentResult::to_json() const {
  Json groups_j = Json::array();
  for (const auto& g : groups)
    groups_j.push_back({{"analytic", g.analytic}, {"multiplicity", g.multiplicity}, {"learned_count", g.used},
                        {"learned_mean", g.learned_mean}, {"rel_err", g.rel_err}});
  return Json{{"shape", to_string(spec.kind)},
              {"dimensions", {{"radius", spec.radius}, {"major", spec.major}, {"length", spec.length}, {"side", spec.side}}},
              {"config", config.to_json()},
              {"eval_points", eval_points},
              {"learned_eigenvalues", std::vector<double>(learned.data(), learned.data() + learned.size())},
              {"groups", groups_j},
              {"max_group_rel_err", max_group_rel_err},
              {"first_loss", train.first_loss},
              {"final_loss", train.final_loss},
              {"train_seconds", train_seconds},
              {"readout_seconds", readout_seconds},
              {"sampler_uniformity", {{"points", sampler_uniformity.points}, {"cells", sampler_uniformity.cells},
                                      {"chi2_per_dof", sampler_uniformity.chi2_per_dof},
                                      {"max_rel_dev", sampler_uniformity.max_rel_dev}}}};
}

std::string ShapeExperimentResult::table_markdown() const {
  std::string s = "| group | analytic λ | multiplicity | learned (count) | learned mean λ | rel. error |\n"
                  "|---|---|---|---|---|---|\n";
  char line[256];
  for (size_t i = 0; i < groups.size(); ++i) {
    const auto& g = groups[i];
    std::snprintf(line, sizeof line, "| %zu | %.6g | %d | %d | %.6g | %.2e |\n", i + 1, g.analytic, g.multiplicity,
                  g.used, g.learned_mean, g.rel_err);
    s += line;
  }
  return s;
}

}  // namespace sgnlf::spectral
