// The methods (runtime/pipeline/methods/): every registered method is described once, its
// config carries exactly its sections, and it composes its step from the parts in its order.
#include <catch2/catch.hpp>

#include <set>

#include "pipeline/methods/registry.hpp"
#include "pipeline/presets.hpp"
#include "pipeline/step_policy.hpp"

using namespace sgnlf;
using namespace sgnlf::pipeline;

namespace {

// Parts that only record what was asked of them, in order.
class RecordingParts : public StepParts {
 public:
  struct Policy : StepPolicy {
    void step(LidarNerfModel&, uint64_t, long, float) override {}
  };
  std::vector<std::string> calls;
  StepPolicy& ground_truth_poses() override { return record("ground_truth_poses"); }
  StepPolicy& pose_free() override { return record("pose_free"); }
  StepPolicy& consistency(StepPolicy&) override { return record("consistency"); }
  StepPolicy& spectral(StepPolicy&) override { return record("spectral"); }

 private:
  StepPolicy& record(const std::string& what) {
    calls.push_back(what);
    return policy_;
  }
  Policy policy_;
};

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

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
  CHECK_FALSE(resolve_config("sg-nlf-no-graph", "smoke").confidence_graph());
}
