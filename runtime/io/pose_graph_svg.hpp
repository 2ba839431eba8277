// A top view (x right, y up, metres, equal axes) of a pose graph over its trajectory as an SVG
// picture: the trajectory as a polyline with a dot per frame (every fifth numbered), each edge
// a straight segment between its two frames, shaded by its weight (opacity and width grow with
// weight / largest weight): sequential edges in blue, non-adjacent edges in red, a legend with
// their counts and a scale bar. An optional reference trajectory (e.g. ground truth) is drawn
// underneath in grey. For SG-NLF's confidence-aware pose graph (method.md §4.2).
#pragma once
#include <string>
#include <vector>

#include "geometry/se3.hpp"

namespace sgnlf::io {

struct SvgGraphEdge {
  int i = 0, j = 0;
  double weight = 1.0;  // finite, >= 0
  bool sequential = true;
};

// IoError naming the file when it cannot be written; Error for no poses, a non-finite pose or
// weight, an edge outside the trajectory, or a reference of another length.
void write_pose_graph_svg(const std::string& path, const std::string& title,
                          const std::vector<Pose>& T_world_lidar,
                          const std::vector<SvgGraphEdge>& edges,
                          const std::vector<Pose>& reference = {});

}  // namespace sgnlf::io
