// The analytic-surface check of method.md §4.1: train Ψ on a shape, Rayleigh–Ritz on a
// quasi-uniform lattice of ≥ 400k points, compare each eigenvalue group with the analytic
// spectrum. Shared by `sgnlf spectral`, the tests and the README tables.
#pragma once
#include "spectral/spectral_trainer.hpp"
#include "spectral/uniformity.hpp"

namespace sgnlf::spectral {

struct ShapeExperimentResult {
  ShapeSpec spec;
  SpectralTrainConfig config;
  size_t eval_points = 0;
  std::vector<SpectrumGroup> analytic;
  Eigen::VectorXd learned;
  std::vector<GroupError> groups;
  double max_group_rel_err = 0;
  SpectralTrainSummary train;
  double train_seconds = 0, readout_seconds = 0;
  UniformityStats sampler_uniformity;  // the training sampler on 32 × 16 equal-area cells
  Json to_json() const;
  std::string table_markdown() const;
};

// Trains `trainer` (fresh) on `shape` and reads out on its lattice of about eval_points points.
ShapeExperimentResult run_shape_experiment(SpectralTrainer& trainer, const ShapeSpec& spec,
                                           size_t eval_points,
                                           const std::function<void(int, double)>& on_step = {});

// Ψ's first n_funcs eigenfunctions over the shape's chart (tile_w × tile_h each), for pictures.
std::vector<float> chart_maps(SpectralTrainer& trainer, const Shape& shape, int n_funcs, int tile_w, int tile_h);

}  // namespace sgnlf::spectral
