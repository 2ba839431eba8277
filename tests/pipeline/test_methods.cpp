// The methods (runtime/pipeline/methods/) and the presets' "extends": every registered method
// is described once, its config carries exactly its sections, it composes its step from the
// parts in its own order, and a preset that extends another resolves to the whole config.
#include <catch2/catch.hpp>

#include <set>

#include "config_error.hpp"
#include "core/config.hpp"
#include "pipeline/methods/registry.hpp"
#include "pipeline/config/presets.hpp"
#include "pipeline/train/step_policy.hpp"

using namespace sgnlf;
using namespace sgnlf::pipeline;
using sgnlf::test::error_of;

namespace {

// Parts that only record what was asked of them, in order.
class RecordingParts : public StepParts {
 public:
  struct Policy : StepPolicy {
    void step(LidarNerfModel&, FieldOptimizer&, uint64_t, long, float) override {}
  };
  std::vector<std::string> calls;
  StepPolicy& ground_truth_poses() override { return record("ground_truth_poses"); }
  StepPolicy& pose_free() override { return record("pose_free"); }
  StepPolicy& consistency(StepPolicy&) override { return record("consistency"); }
  StepPolicy& spectral(StepPolicy&) override { return record("spectral"); }
  StepPolicy& scene_flow(StepPolicy&) override { return record("scene_flow"); }

 private:
  StepPolicy& record(const std::string& what) {
    calls.push_back(what);
    return policy_;
  }
  Policy policy_;
};


}  // namespace

TEST_CASE("every method is described once and composes its step from the parts",
          "[pipeline][config][methods]") {
  std::set<std::string> names;
  for (const Method& m : method_registry()) {
    CAPTURE(m.name);
    CHECK(names.insert(m.name).second);  // no name twice
    CHECK_FALSE(m.description.empty());
    CHECK(&find_method(m.name) == &m);
    CHECK(m.implemented == (m.compose != nullptr));
    if (!m.implemented) continue;
    for (const char* scale : {"smoke", "quick", "paper"}) {
      CAPTURE(scale);
      const TrainConfig c = resolve_config(m.name, scale);
      CHECK(c.method == m.name);
      // The config carries exactly the method's sections.
      CHECK(c.pose_free.has_value() == m.sections.pose_free);
      CHECK(c.spectral.has_value() == m.sections.spectral);
      CHECK(c.pose_graph.has_value() == m.sections.pose_graph);
      CHECK(c.consistency.has_value() == m.sections.consistency);
      CHECK(c.lidar4d.has_value() == m.sections.lidar4d);
    }
  }
  CHECK(error_of([] { find_method("lidar5d"); }).find("known: lidar-nerf") != std::string::npos);
  auto composed = [](const std::string& name) {
    RecordingParts p;
    find_method(name).compose(p);
    return p.calls;
  };
  using V = std::vector<std::string>;
  CHECK(composed("lidar-nerf") == V{"ground_truth_poses"});
  // The flow supervision wraps the ground-truth-pose step (its gradient joins that update).
  CHECK(composed("lidar4d") == V{"ground_truth_poses", "scene_flow"});
  CHECK(composed("geonlf") == V{"pose_free"});
  CHECK(composed("geonlf-frozen") == V{"pose_free"});
  // Ψ's schedule wraps the consistency, which wraps the pose-free step (it sets λ(t) first).
  CHECK(composed("sg-nlf") == V{"pose_free", "consistency", "spectral"});
  // The ablations are SG-NLF with a section off or absent: the parts leave those out.
  CHECK(composed("sg-nlf-baseline") == V{"pose_free", "consistency", "spectral"});
  CHECK_FALSE(resolve_config("sg-nlf-baseline", "smoke").hybrid_encoder());
  CHECK_FALSE(resolve_config("sg-nlf-baseline", "smoke").confidence_graph());
  CHECK_FALSE(resolve_config("sg-nlf-baseline", "smoke").consistency_term());
  CHECK(resolve_config("sg-nlf-no-graph", "smoke").hybrid_encoder());
  // Spectral only: SG-NLF's field without the hash grid, Ψ at full weight from the first step.
  CHECK(composed("sg-nlf-spectral-only") == V{"pose_free", "consistency", "spectral"});
  for (const char* scale : {"smoke", "quick", "paper"}) {
    const TrainConfig so = resolve_config("sg-nlf-spectral-only", scale);
    REQUIRE(so.hybrid_encoder());
    CHECK_FALSE(so.spectral->geometric);
    CHECK(so.spectral->fusion.lambda(0) == 1.0);
    CHECK(resolve_config("sg-nlf", scale).spectral->geometric);
    CHECK(so.confidence_graph() == resolve_config("sg-nlf", scale).confidence_graph());
  }
  CHECK_FALSE(resolve_config("sg-nlf-no-graph", "smoke").confidence_graph());
  // The ground-truth-pose control: SG-NLF's field on the true poses, which nothing moves.
  CHECK(composed("sg-nlf-gt-poses") == V{"pose_free", "consistency", "spectral"});
  for (const char* scale : {"smoke", "quick", "paper"}) {
    const TrainConfig c = resolve_config("sg-nlf-gt-poses", scale);
    CHECK(c.pose_free->poses.init == "gt");
    CHECK_FALSE(c.pose_free->pose_optim.optimize);
    CHECK_FALSE(c.geometric_stage());
    // Starting from the odometry does not bring the preset's geometric section back.
    CHECK_FALSE(
        resolve_config("sg-nlf-gt-poses", scale, Json{{"poses", {{"init", "odometry"}}}})
            .geometric_stage());
    CHECK_FALSE(c.confidence_graph());
    CHECK(c.hybrid_encoder());
    CHECK(c.consistency_term());
  }
}

namespace {
// Every key path of `part` exists in `whole`.
bool has_paths(const Json& whole, const Json& part) {
  for (auto it = part.begin(); it != part.end(); ++it) {
    if (!whole.contains(it.key())) return false;
    if (it.value().is_object() && !has_paths(whole.at(it.key()), it.value())) return false;
  }
  return true;
}
}  // namespace

TEST_CASE("a preset that extends another resolves to the whole config",
          "[pipeline][config][presets]") {
  const PresetTexts texts = {
      {"a", R"({"method": "geonlf", "field": {"levels": 8, "geo_features": 15},
                "geometric": {"edge_offsets": [1, 2]}, "from_odometry": {"pose_optim": {"lr_rot": 1}}})"},
      {"b", R"({"extends": "a", "field": {"levels": 4}, "geometric": {"edge_offsets": [3]},
                "from_odometry": {"pose_optim": {"start_step": 5}}})"},
      {"c", R"({"extends": "b", "method": "sg-nlf"})"},
      {"loop1", R"({"extends": "loop2"})"},
      {"loop2", R"({"extends": "loop1"})"},
      {"orphan", R"({"extends": "nowhere"})"},
      {"bad", R"({"extends": 3})"},
  };
  const Json c = resolve_preset("c", texts);
  CHECK_FALSE(c.contains("extends"));
  CHECK(c["method"] == "sg-nlf");
  CHECK(c["field"] == Json{{"levels", 4}, {"geo_features", 15}});       // merged key by key
  CHECK(c["geometric"]["edge_offsets"] == Json::array({3}));            // arrays replaced
  CHECK(c["from_odometry"]["pose_optim"] == Json{{"lr_rot", 1}, {"start_step", 5}});
  CHECK(resolve_preset("a", texts) == Json::parse(texts[0].second));    // no extends: as written
  CHECK(error_of([&] { resolve_preset("loop1", texts); }).find("cycle") != std::string::npos);
  CHECK(error_of([&] { resolve_preset("orphan", texts); }).find("orphan: 'extends' = \"nowhere\"") !=
        std::string::npos);
  CHECK(error_of([&] { resolve_preset("bad", texts); }).find("bad: 'extends'") != std::string::npos);

  // The embedded SG-NLF presets extend GeoNLF's: everything GeoNLF's preset holds is there.
  for (const char* scale : {"smoke", "quick", "paper"}) {
    CAPTURE(scale);
    const Json sg = preset_json("sg-nlf", scale), geo = preset_json("geonlf", scale);
    CHECK_FALSE(sg.contains("extends"));
    CHECK(has_paths(sg, geo));
    CHECK(sg["field"] == geo["field"]);
    CHECK(has_paths(odometry_start_json("sg-nlf", scale), odometry_start_json("geonlf", scale)));
  }
}
