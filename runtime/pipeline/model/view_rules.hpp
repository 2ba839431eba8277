// The evaluation-time rules a rendered range image passes through before it is scored or
// written (render.eval_depth "mix", render.eval_drop_out_of_range): shared by render_view and
// the evaluation's depth diagnostics (pipeline/run/evaluate.cpp). Host-side, per frame.
#pragma once
#include <cstddef>
#include <vector>

#include "geometry/range_image.hpp"
#include "geometry/sensor.hpp"
#include "pipeline/model/render_view.hpp"

namespace sgnlf::pipeline {

// GS-LiDAR's "mix" depth: a ray whose weight-normalised depth variance exceeds `factor` (GS-LiDAR:
// 10, render.eval_mix_factor's default and the evaluation's mix_* diagnostics) times the frame's
// median variance straddles two surfaces (an edge, a blurred boundary), so its expected depth
// Σ w t would lie between them; it takes the median depth instead.
constexpr double kMixVarianceFactor = 10.0;

// factor × the median of `variance_m2` (the frame's rays). Requires a non-empty frame.
double mix_variance_threshold(const std::vector<float>& variance_m2,
                              double factor = kMixVarianceFactor);

// Replaces the range of every pixel whose variance exceeds mix_variance_threshold() by its
// median depth (metres). `stats` must describe `img` (one entry per pixel). Returns the number
// of pixels replaced.
size_t apply_mix_depth(RangeImage& img, const DepthStats& stats,
                       double factor = kMixVarianceFactor);

// A predicted return (ray_drop > 0.5) at a range the sensor cannot report (outside
// Sensor::in_range: within min_range_m, the vehicle itself, or at or beyond max_range_m) becomes
// a drop (ray_drop = 0), as the loaders treat such points in the observed images. Returns the
// number of pixels changed.
size_t drop_out_of_range(RangeImage& img, const Sensor& sensor);

}  // namespace sgnlf::pipeline
