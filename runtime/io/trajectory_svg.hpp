// A top view (x right, y up, metres, equal axes) of several trajectories as an SVG picture:
// one polyline per trajectory with a dot per pose and a marker at its first pose, a legend, a
// scale bar, and optional thin segments joining corresponding poses of two trajectories (e.g.
// each optimised pose to its ground truth).
#pragma once
#include <string>
#include <vector>

#include "geometry/se3.hpp"

namespace sgnlf::io {

struct SvgTrajectory {
  std::string name;   // legend text
  std::string color;  // any SVG colour, e.g. "#1f77b4"
  std::vector<Pose> poses;
};

// `links`: pairs of trajectory indices (a, b) whose k-th poses are joined (same lengths).
// IoError naming the file when it cannot be written; Error for empty input or non-finite poses.
void write_trajectory_svg(const std::string& path, const std::string& title,
                          const std::vector<SvgTrajectory>& trajectories,
                          const std::vector<std::pair<int, int>>& links = {});

}  // namespace sgnlf::io
