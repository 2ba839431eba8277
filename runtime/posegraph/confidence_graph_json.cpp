// confidence_graph_json (see confidence_graph.hpp): what a run folder keeps of each graph.
#include <cmath>

#include "core/config.hpp"
#include "posegraph/confidence_graph.hpp"

namespace sgnlf::posegraph {

Json confidence_graph_json(const ConfidenceGraph& g) {
  auto finite_or_null = [](double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); };
  Json pairs = Json::array();
  for (const auto& r : g.pairs)
    pairs.push_back(Json{{"i", r.i},
                         {"j", r.j},
                         {"sequential", r.sequential},
                         {"E", r.compatibility},
                         {"alpha", r.alpha},
                         {"weight", r.weight},
                         {"n_matches", r.matches},
                         {"coarse_matches", r.coarse_matches},
                         {"centre_distance_m", r.centre_distance_m},
                         {"valid", r.valid},
                         {"kept", r.kept}});
  return Json{{"frames", g.frames},
              {"threshold", finite_or_null(g.threshold)},
              {"sequential_mean", g.sequential_mean},
              {"sequential_std", g.sequential_std},
              {"edges_in_graph", g.edges.size()},
              {"non_adjacent_edges", g.non_adjacent_edges()},
              {"edges", pairs}};
}

}  // namespace sgnlf::posegraph
