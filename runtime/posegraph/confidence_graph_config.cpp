// ConfidenceGraphConfig validation and JSON (see confidence_graph_config.hpp).
#include "posegraph/confidence_graph_config.hpp"

#include <cmath>
#include <set>

namespace sgnlf::posegraph {
namespace {

const char* kWhere = "confidence graph";

void check(bool ok, const std::string& key, const std::string& value, const char* rule) {
  if (!ok) throw ConfigError(std::string(kWhere) + ": '" + key + "' = " + value + ": " + rule);
}

void check_positive(const std::string& key, double v) {
  check(std::isfinite(v) && v > 0.0, key, std::to_string(v), "must be finite and > 0");
}

}  // namespace

void ConfidenceGraphConfig::validate() const {
  check(!sequential_offsets.empty(), "sequential_offsets", "[]", "needs at least one offset");
  std::set<int> seen;
  for (int o : sequential_offsets) {
    check(o >= 1, "sequential_offsets", std::to_string(o), "every offset must be >= 1");
    check(seen.insert(o).second, "sequential_offsets", std::to_string(o), "repeated offset");
  }
  check(std::isfinite(candidate_distance_m) && candidate_distance_m >= 0.0,
        "candidate_distance_m", std::to_string(candidate_distance_m), "must be finite and >= 0");
  check(min_index_gap >= 0, "min_index_gap", std::to_string(min_index_gap), "must be >= 0");
  check_positive("coarse_voxel_m", coarse_voxel_m);
  check_positive("coarse_radius_m", coarse_radius_m);
  check_positive("fine_radius_m", fine_radius_m);
  check(min_matches >= 2, "min_matches", std::to_string(min_matches),
        "must be >= 2 (α needs a pair of matches)");
  check(std::isfinite(min_match_fraction) && min_match_fraction >= 0.0 &&
            min_match_fraction <= 1.0,
        "min_match_fraction", std::to_string(min_match_fraction), "must be in [0, 1]");
  check(std::isfinite(kappa), "kappa", std::to_string(kappa), "must be finite");
  check_positive("sigma_d_m", sigma_d_m);
  check(max_alpha_pairs >= 1, "max_alpha_pairs", std::to_string(max_alpha_pairs),
        "must be >= 1");
  check(reevaluate_every >= 1, "reevaluate_every", std::to_string(reevaluate_every),
        "must be >= 1");
  check(std::isfinite(edge_max_distance_m) && edge_max_distance_m >= 0.0, "edge_max_distance_m",
        std::to_string(edge_max_distance_m), "must be finite and >= 0 (0: off)");
  check(threads >= 1 && threads <= 256, "threads", std::to_string(threads),
        "must be in [1, 256]");
}

ConfidenceGraphConfig ConfidenceGraphConfig::from_json(ConfigReader& r) {
  ConfidenceGraphConfig c;
  r.get("sequential_offsets", c.sequential_offsets)
      .get("candidate_distance_m", c.candidate_distance_m)
      .get("min_index_gap", c.min_index_gap)
      .get("match_points", c.match_points)
      .get("coarse_voxel_m", c.coarse_voxel_m)
      .get("coarse_radius_m", c.coarse_radius_m)
      .get("fine_radius_m", c.fine_radius_m)
      .get("coarse_to_fine", c.coarse_to_fine)
      .get("min_matches", c.min_matches)
      .get("min_match_fraction", c.min_match_fraction)
      .get("kappa", c.kappa)
      .get("compatibility_test", c.compatibility_test)
      .get("sigma_d_m", c.sigma_d_m)
      .get("max_alpha_pairs", c.max_alpha_pairs)
      .get("alpha_weights", c.alpha_weights)
      .get("reevaluate_every", c.reevaluate_every)
      .get("edge_max_distance_m", c.edge_max_distance_m)
      .get("seed", c.seed)
      .get("threads", c.threads);
  try {
    c.validate();
  } catch (const ConfigError& e) {
    throw ConfigError(r.where() + ": " + e.what());
  }
  return c;
}

ConfidenceGraphConfig ConfidenceGraphConfig::from_json(const Json& j, const std::string& where) {
  ConfigReader r(j, where);
  ConfidenceGraphConfig c = from_json(r);
  r.finish();
  return c;
}

Json ConfidenceGraphConfig::to_json() const {
  Json j{{"sequential_offsets", sequential_offsets},
         {"candidate_distance_m", candidate_distance_m},
         {"min_index_gap", min_index_gap},
         {"match_points", match_points},
         {"coarse_voxel_m", coarse_voxel_m},
         {"coarse_radius_m", coarse_radius_m},
         {"fine_radius_m", fine_radius_m},
         {"coarse_to_fine", coarse_to_fine},
         {"min_matches", min_matches},
         {"min_match_fraction", min_match_fraction},
         {"kappa", kappa},
         {"compatibility_test", compatibility_test},
         {"sigma_d_m", sigma_d_m},
         {"max_alpha_pairs", max_alpha_pairs},
         {"alpha_weights", alpha_weights},
         {"reevaluate_every", reevaluate_every},
         {"seed", seed},
         {"threads", threads}};
  if (edge_max_distance_m > 0.0) j["edge_max_distance_m"] = edge_max_distance_m;
  return j;
}

}  // namespace sgnlf::posegraph
