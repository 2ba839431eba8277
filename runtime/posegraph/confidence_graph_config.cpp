// ConfidenceGraphConfig validation and JSON (see confidence_graph_config.hpp).
#include "core/config_fields.hpp"
#include "posegraph/confidence_graph_config.hpp"

#include <cmath>
#include <set>

#include "core/config.hpp"

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
  config::check_fields(*this, kWhere);
  check(!sequential_offsets.empty(), "sequential_offsets", "[]", "needs at least one offset");
  std::set<int> seen;
  for (int o : sequential_offsets) {
    check(o >= 1, "sequential_offsets", std::to_string(o), "every offset must be >= 1");
    check(seen.insert(o).second, "sequential_offsets", std::to_string(o), "repeated offset");
  }
  check(std::isfinite(candidate_distance_m) && candidate_distance_m >= 0.0,
        "candidate_distance_m", std::to_string(candidate_distance_m), "must be finite and >= 0");
  check_positive("coarse_voxel_m", coarse_voxel_m);
  check_positive("coarse_radius_m", coarse_radius_m);
  check_positive("fine_radius_m", fine_radius_m);
  check(std::isfinite(kappa), "kappa", std::to_string(kappa), "must be finite");
  check_positive("sigma_d_m", sigma_d_m);
  check(std::isfinite(edge_max_distance_m) && edge_max_distance_m >= 0.0, "edge_max_distance_m",
        std::to_string(edge_max_distance_m), "must be finite and >= 0 (0: off)");
}

ConfidenceGraphConfig ConfidenceGraphConfig::from_json(ConfigReader& r) {
  ConfidenceGraphConfig c;
  config::read_fields_here(r, c);
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

Json ConfidenceGraphConfig::to_json() const { return config::write_fields(*this); }

}  // namespace sgnlf::posegraph
