// The edge set of the geometric pose graph: an edge (i, j, weight) contributes
// weight · (robust Chamfer i→j + j→i) to the loss (method.md §3 GeoNLF, §4.2 SG-NLF's α^ij).
// GeoNLF's default graph is sequential: (i, i+1) and (i, i+2), weight 1. SG-NLF's pose graph
// passes its own weighted list (non-adjacent edges with weights α) through the same struct.
#pragma once
#include <vector>

namespace sgnlf::posegraph {

struct Edge {
  int i = 0, j = 0;     // frame indices, i ≠ j
  double weight = 1.0;  // ≥ 0, finite
};

// (i, i + o, 1.0) for every offset o and every i with i + o < n_frames, ordered by offset then
// i. GeoNLF: offsets {1, 2}. Throws sgnlf::ConfigError for an offset < 1.
std::vector<Edge> sequential_edges(int n_frames, const std::vector<int>& offsets = {1, 2});

// Throws sgnlf::Error naming the first bad edge (index out of range, i == j, bad weight) or an
// empty edge list.
void validate_edges(const std::vector<Edge>& edges, int n_frames);

}  // namespace sgnlf::posegraph
