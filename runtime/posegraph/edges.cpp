// Edge generators and validation for the geometric pose graph.
#include "posegraph/edges.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"

namespace sgnlf::posegraph {

std::vector<Edge> sequential_edges(int n_frames, const std::vector<int>& offsets) {
  std::vector<Edge> edges;
  for (int o : offsets) {
    if (o < 1)
      throw ConfigError("sequential_edges: edge offset must be >= 1, got " + std::to_string(o));
    for (int i = 0; i + o < n_frames; ++i) edges.push_back(Edge{i, i + o, 1.0});
  }
  return edges;
}

void validate_edges(const std::vector<Edge>& edges, int n_frames) {
  require(!edges.empty(), "pose graph: the edge list is empty (" + std::to_string(n_frames) +
                              " frames)");
  for (size_t k = 0; k < edges.size(); ++k) {
    const Edge& e = edges[k];
    const std::string name = "pose graph: edge " + std::to_string(k) + " (" +
                             std::to_string(e.i) + ", " + std::to_string(e.j) + ")";
    require(e.i >= 0 && e.j >= 0 && e.i < n_frames && e.j < n_frames,
            name + " refers to a frame outside [0, " + std::to_string(n_frames) + ")");
    require(e.i != e.j, name + " joins a frame to itself");
    require(std::isfinite(e.weight) && e.weight >= 0.0,
            name + " has weight " + std::to_string(e.weight) + " (must be finite and >= 0)");
  }
}

}  // namespace sgnlf::posegraph
