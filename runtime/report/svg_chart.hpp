// Line charts as inline SVG, drawn by our own code (no charting library, no script): axes with
// 1-2-5 ticks (powers of ten on a log axis), a grid, one polyline per series and a legend.
// Used for the training curves and, with equal axes, for trajectories seen from above.
#pragma once
#include <string>
#include <vector>

namespace sgnlf::report {

struct ChartSeries {
  std::string name, color;  // legend text; any SVG colour ("#1f77b4")
  std::vector<double> x, y; // same length; non-finite points (and y ≤ 0 on a log axis) are skipped
  bool dots = false;        // a dot at every point as well as the line
};

struct ChartOptions {
  std::string title, x_label, y_label;
  bool log_y = false;
  bool equal_axes = false;  // one metre is as long on both axes (top views)
  int width = 540, height = 280;
};

// <svg class="chart" ...>…</svg>; a chart without any drawable point says "no data".
std::string svg_chart(const std::vector<ChartSeries>& series, const ChartOptions& opt);

// Tick positions covering [lo, hi] at a 1-2-5 step, about `target` of them.
std::vector<double> nice_ticks(double lo, double hi, int target = 5);

}  // namespace sgnlf::report
