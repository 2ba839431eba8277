// TrainConfig and presets: strict JSON (unknown keys and bad values are named), every embedded
// preset resolves, overrides merge key by key, the learning-rate schedule decays to 0.1×.
#include <catch2/catch.hpp>

#include "config_error.hpp"
#include "core/config.hpp"
#include "pipeline/config/presets.hpp"

using namespace sgnlf;
using namespace sgnlf::pipeline;
using sgnlf::test::error_of;

TEST_CASE("every embedded preset resolves and validates", "[pipeline][config]") {
  const auto names = preset_names();
  REQUIRE(names.size() >= 3);
  for (const char* p : {"paper", "quick", "smoke"}) {
    const TrainConfig c = resolve_config("lidar-nerf", p);
    CHECK(c.preset == p);
    CHECK(c.method == "lidar-nerf");
  }
  // paper = method.md §1 published values.
  const TrainConfig paper = resolve_config("lidar-nerf", "paper");
  CHECK(paper.schedule.iterations == 30000);
  CHECK(paper.schedule.rays_per_batch == 4096);
  CHECK(paper.render.n_samples == 768);
  CHECK(paper.render.n_importance == 64);
  CHECK(paper.field.grid.log2_table_size == 19);
  CHECK(paper.field.grid.deterministic);  // the paper's default: the bit-reproducible backward
  CHECK(paper.optim.lr == Approx(1e-2));
}

TEST_CASE("unknown keys are rejected with their name", "[pipeline][config]") {
  Json j = preset_json("lidar-nerf", "smoke");
  j["schedule"]["iteratons"] = 5;
  const std::string e = error_of([&] { train_config_from_json(j, "x.json"); });
  CHECK(e.find("iteratons") != std::string::npos);
  CHECK(e.find("x.json") != std::string::npos);
  Json top = preset_json("lidar-nerf", "smoke");
  top["bogus"] = 1;
  CHECK(error_of([&] { train_config_from_json(top, "y"); }).find("bogus") != std::string::npos);
  Json render = preset_json("lidar-nerf", "smoke");
  render["render"]["n_sample"] = 3;
  CHECK(error_of([&] { train_config_from_json(render, "z"); }).find("n_sample") != std::string::npos);
}

TEST_CASE("the modules' configs are embedded whole, with their keys and checks",
          "[pipeline][config]") {
  // The hash grid's every key, the presets' values as before (deterministic by default).
  for (const char* method : {"lidar-nerf", "geonlf", "sg-nlf"})
    for (const char* p : {"smoke", "quick", "paper"}) {
      CAPTURE(method, p);
      const TrainConfig c = resolve_config(method, p);
      CHECK(c.field.grid.deterministic);
      CHECK_FALSE(c.field.grid.half_table);
      CHECK(c.field.grid.schedule == "auto");
      CHECK(c.optim.adam.beta1 == 0.9f);
      CHECK(c.optim.adam.beta2 == 0.99f);
      CHECK(c.optim.adam.eps == 1e-15f);
      CHECK(c.optim.adam.weight_decay == 0.0f);
      const Json j = train_config_to_json(c);
      CHECK(j["field"]["grid"].size() == 8);  // every key of field::HashGridConfig written
      CHECK(j["optim"]["adam"].size() == 4);
    }
  const TrainConfig geo = resolve_config("geonlf", "quick");
  CHECK(geo.field.grid.levels == 14);
  CHECK(geo.field.grid.per_level_scale == 1.511f);
  CHECK(geo.pose_free->geometric->optimizer.lr_rotation == 0.01);
  CHECK(geo.pose_free->geometric->optimizer.points_per_frame == 4000);
  CHECK(geo.pose_free->geometric->optimizer.min_distance == 0.15);  // the module's, now a key
  const Json geo_json = train_config_to_json(geo);
  CHECK(geo_json["geometric"]["optimizer"]["normals"]["min_neighbours"] == 6);
  CHECK_FALSE(geo_json["geometric"]["optimizer"].contains("steps"));  // per call, not a key

  // An option the old copy fixed reaches the config and its hash.
  const TrainConfig half =
      resolve_config("lidar-nerf", "smoke", Json{{"field", {{"grid", {{"half_table", true}}}}}});
  CHECK(half.field.grid.half_table);
  CHECK(half.hash() != resolve_config("lidar-nerf", "smoke").hash());
  const TrainConfig atomic = resolve_config(
      "lidar-nerf", "smoke", Json{{"field", {{"grid", {{"deterministic", false}}}}}});
  CHECK_FALSE(atomic.field.grid.deterministic);
  CHECK(train_config_from_json(train_config_to_json(atomic), "rt").hash() == atomic.hash());

  // Unknown keys inside an embedded section are refused, naming its path.
  auto lidar_nerf_error = [](const Json& o) {
    return error_of([&] { resolve_config("lidar-nerf", "smoke", o, "mine.json"); });
  };
  std::string e = lidar_nerf_error(Json{{"field", {{"grid", {{"half_tabel", true}}}}}});
  CHECK(e.find("mine.json.field.grid: unknown key(s) 'half_tabel'") != std::string::npos);
  CHECK(e.find("did you mean 'half_table'") != std::string::npos);
  e = lidar_nerf_error(Json{{"optim", {{"adam", {{"beta3", 0.5}}}}}});
  CHECK(e.find("mine.json.optim.adam: unknown key(s) 'beta3'") != std::string::npos);
  // The copied keys are gone from the outer section.
  CHECK(lidar_nerf_error(Json{{"field", {{"levels", 8}}}}).find("field: unknown key(s) 'levels'") !=
        std::string::npos);
  CHECK(lidar_nerf_error(Json{{"optim", {{"beta1", 0.9}}}}).find("optim: unknown key(s) 'beta1'") !=
        std::string::npos);
  e = error_of([] {
    resolve_config("geonlf", "smoke", Json{{"geometric", {{"optimizer", {{"lr_rot", 0.1}}}}}}, "o");
  });
  CHECK(e.find("o.geometric.optimizer: unknown key(s) 'lr_rot'") != std::string::npos);
  e = error_of([] {
    resolve_config("geonlf", "smoke",
                   Json{{"geometric", {{"optimizer", {{"normals", {{"radius", 1.0}}}}}}}}, "o");
  });
  CHECK(e.find("o.geometric.optimizer.normals: unknown key(s) 'radius'") != std::string::npos);
  // The modules' own checks, naming the path and the key.
  e = lidar_nerf_error(Json{{"field", {{"grid", {{"features", 3}}}}}});
  CHECK(e.find("config.field.grid: 'features' = 3") != std::string::npos);
  e = lidar_nerf_error(Json{{"field", {{"grid", {{"schedule", "fast"}}}}}});
  CHECK(e.find("config.field.grid: 'schedule'") != std::string::npos);
  e = lidar_nerf_error(Json{{"optim", {{"adam", {{"beta1", 1.5}}}}}});
  CHECK(e.find("config.optim.adam: 'beta1'") != std::string::npos);
  e = error_of([] {
    resolve_config("geonlf", "smoke", Json{{"geometric", {{"optimizer", {{"min_distance", 0.0}}}}}});
  });
  CHECK(e.find("config.geometric.optimizer.min_distance") != std::string::npos);
}

TEST_CASE("a section's presence is its only switch", "[pipeline][config]") {
  // Taken out with null (JSON merge patch), the feature is off and the section not written.
  const TrainConfig sg = resolve_config("sg-nlf", "smoke");
  CHECK(sg.hybrid_encoder());
  CHECK(sg.confidence_graph());
  CHECK(sg.consistency_term());
  CHECK(sg.geometric_stage());
  CHECK(sg.reweighting());
  const TrainConfig bare = resolve_config(
      "sg-nlf", "smoke",
      Json{{"spectral", nullptr}, {"pose_graph", nullptr}, {"consistency", nullptr},
           {"geometric", nullptr}, {"reweight", nullptr}});
  CHECK_FALSE(bare.hybrid_encoder());
  CHECK_FALSE(bare.confidence_graph());
  CHECK_FALSE(bare.consistency_term());
  CHECK_FALSE(bare.geometric_stage());
  CHECK_FALSE(bare.reweighting());
  const Json bare_json = train_config_to_json(bare);
  for (const char* k : {"spectral", "pose_graph", "consistency", "geometric", "reweight"})
    CHECK_FALSE(bare_json.contains(k));
  CHECK(train_config_from_json(bare_json, "rt").hash() == bare.hash());
  // The ablation rows are SG-NLF without the sections: the same configs but the name.
  Json no_graph = train_config_to_json(resolve_config("sg-nlf-no-graph", "smoke"));
  Json sg_no_graph = train_config_to_json(resolve_config("sg-nlf", "smoke", Json{{"pose_graph", nullptr}}));
  no_graph.erase("method");
  sg_no_graph.erase("method");
  CHECK(no_graph == sg_no_graph);
  // A method that cannot carry a section refuses it.
  CHECK(error_of([] {
          resolve_config("sg-nlf-no-hybrid", "smoke", Json{{"spectral", {{"every", 2}}}});
        }).find("'spectral'") != std::string::npos);
  // An old config's switch is refused with what to do, on and off alike, in every section.
  const std::pair<const char*, Json> old_switches[] = {
      {"spectral", Json{{"spectral", {{"enabled", false}}}}},
      {"pose_graph", Json{{"pose_graph", {{"enabled", false}}}}},
      {"consistency", Json{{"consistency", {{"enabled", true}}}}},
      {"geometric", Json{{"geometric", {{"enabled", false}}}}},
      {"reweight", Json{{"reweight", {{"enabled", false}}}}}};
  for (const auto& [section, o] : old_switches) {
    CAPTURE(section);
    const std::string e = error_of([&] { resolve_config("sg-nlf", "smoke", o, "old.json"); });
    CHECK(e.find("old.json." + std::string(section) + ": 'enabled' is not a key") !=
          std::string::npos);
    CHECK(e.find("remove the section (in overrides: \"" + std::string(section) + "\": null)") !=
          std::string::npos);
  }
  // The geometric stage moves the poses: beside frozen poses it is refused, not ignored.
  CHECK(error_of([] {
          resolve_config("geonlf", "smoke", Json{{"pose_optim", {{"optimize", false}}}});
        }).find("config.geometric: the geometric stage moves the poses") != std::string::npos);
  CHECK_FALSE(resolve_config("geonlf-frozen", "smoke").geometric_stage());
  // merge_config_json records a removal at any depth, so that layers of overrides compose;
  // drop_removed_keys applies them.
  const Json layer = merge_config_json(Json{{"spectral", {{"every", 2}}}}, Json{{"spectral", nullptr}});
  CHECK(layer == Json{{"spectral", nullptr}});
  CHECK_FALSE(resolve_config("sg-nlf", "smoke", layer).hybrid_encoder());
  const Json m = merge_config_json(Json{{"a", {{"b", 1}, {"c", 2}}}},
                                   Json{{"a", {{"b", nullptr}}}, {"d", {{"e", nullptr}, {"f", 3}}}});
  CHECK(drop_removed_keys(m) == Json{{"a", {{"c", 2}}}, {"d", {{"f", 3}}}});
}

TEST_CASE("bad values are named", "[pipeline][config]") {
  Json j = preset_json("lidar-nerf", "smoke");
  j["optim"]["lr"] = -1.0;
  CHECK(error_of([&] { train_config_from_json(j, "c"); }).find("'lr'") != std::string::npos);
  j = preset_json("lidar-nerf", "smoke");
  j["schedule"]["iterations"] = "many";
  CHECK(error_of([&] { train_config_from_json(j, "c"); }).find("iterations") != std::string::npos);
  j = preset_json("lidar-nerf", "smoke");
  j["schedule"]["rays_per_batch"] = 100;  // not a multiple of the 2×8 patch
  CHECK(error_of([&] { train_config_from_json(j, "c"); }).find("rays_per_batch") != std::string::npos);
  j = preset_json("lidar-nerf", "smoke");
  j["render"]["stop_transmittance"] = 0.9;  // a threshold that would cut visible surfaces
  CHECK(error_of([&] { train_config_from_json(j, "c"); }).find("stop_transmittance") != std::string::npos);
  j = preset_json("lidar-nerf", "smoke");
  j["render"]["stop_transmittance"] = 0.0;  // waves need early termination
  j["render"]["coarse_waves"] = 4;
  CHECK(error_of([&] { train_config_from_json(j, "c"); }).find("coarse_waves") != std::string::npos);
  j["render"]["stop_transmittance"] = 1e-4;
  j["render"]["coarse_waves"] = 0;
  CHECK(error_of([&] { train_config_from_json(j, "c"); }).find("coarse_waves") != std::string::npos);
  j["render"]["coarse_waves"] = 4;
  CHECK(train_config_from_json(j, "c").render.coarse_waves == 4);
  CHECK(error_of([&] { preset_json("lidar-nerf", "huge"); }).find("huge") != std::string::npos);
}

TEST_CASE("overrides merge into the preset and round-trip through JSON", "[pipeline][config]") {
  const TrainConfig c =
      resolve_config("lidar-nerf", "quick", Json{{"schedule", {{"iterations", 7}}}});
  CHECK(c.schedule.iterations == 7);
  CHECK(c.schedule.rays_per_batch == resolve_config("lidar-nerf", "quick").schedule.rays_per_batch);
  const TrainConfig back = train_config_from_json(train_config_to_json(c), "rt");
  CHECK(back.hash() == c.hash());
  CHECK(resolve_config("lidar-nerf", "quick").hash() != c.hash());
  // Eval sampling round-trips, is validated, and is absent from the JSON when unset (configs
  // written before it existed keep their hash).
  CHECK_FALSE(train_config_to_json(resolve_config("lidar-nerf", "smoke"))["render"].contains("eval_samples"));
  const TrainConfig e = resolve_config("lidar-nerf", "smoke",
                                       Json{{"render", {{"eval_samples", 96}, {"eval_importance", 0}}}});
  const TrainConfig e_back = train_config_from_json(train_config_to_json(e), "rt");
  CHECK(e_back.render.eval_samples == 96);
  CHECK(e_back.render.eval_importance == 0);
  CHECK(e_back.hash() == e.hash());
  CHECK_THROWS_AS(resolve_config("lidar-nerf", "smoke", Json{{"render", {{"eval_samples", -2}}}}),
                  ConfigError);
}

namespace {
// Every leaf of `part` has the same value in `whole` (nested objects compared key by key); a
// null leaf (a key the section removes) is absent from `whole`.
bool contains_leaves(const Json& whole, const Json& part) {
  for (auto it = part.begin(); it != part.end(); ++it) {
    if (it.value().is_null()) {
      if (whole.contains(it.key())) return false;
      continue;
    }
    if (!whole.contains(it.key())) return false;
    if (it.value().is_object()) {
      if (!contains_leaves(whole.at(it.key()), it.value())) return false;
    } else if (whole.at(it.key()) != it.value()) {
      return false;
    }
  }
  return true;
}
}  // namespace

TEST_CASE("a start from the odometry applies the preset's from_odometry section",
          "[pipeline][config]") {
  const Json odometry{{"poses", {{"init", "odometry"}}}};
  for (const char* method : {"geonlf", "sg-nlf"}) {
    for (const char* p : {"paper", "quick", "smoke"}) {
      CAPTURE(method, p);
      const Json start = odometry_start_json(method, p);
      REQUIRE_FALSE(start.empty());  // every pose-free preset says how it starts from odometry
      CHECK_FALSE(preset_json(method, p).contains("from_odometry"));
      const Json noisy = train_config_to_json(resolve_config(method, p));
      const Json from_odo = train_config_to_json(resolve_config(method, p, odometry));
      CHECK(from_odo["poses"]["init"] == "odometry");
      CHECK(contains_leaves(from_odo, start));  // applied, and valid keys
      CHECK_FALSE(contains_leaves(noisy, start));  // only when starting from the odometry
      // The user's keys still win over the section.
      const Json mine{{"poses", {{"init", "odometry"}}}, {"geometric", {{"first_steps", 7}}}};
      CHECK(resolve_config(method, p, mine).pose_free->geometric->first_steps == 7);
    }
  }
  // Ablations built on a family's preset inherit its section.
  CHECK(resolve_config("sg-nlf-no-graph", "quick", odometry).pose_free->geometric->first_steps ==
        resolve_config("sg-nlf", "quick", odometry).pose_free->geometric->first_steps);
  CHECK(odometry_start_json("lidar-nerf", "quick").empty());
  // A malformed init is still named by the strict reader.
  CHECK(error_of([] { resolve_config("geonlf", "quick", Json{{"poses", {{"init", 5}}}}); })
            .find("init") != std::string::npos);
}

TEST_CASE("thread counts are recorded but left out of the hash; the geometric seed is in it",
          "[pipeline][config]") {
  const TrainConfig sg = resolve_config("sg-nlf", "smoke");
  const Json sg_json = train_config_to_json(sg);
  // The geometric optimiser's every key is written, its seed and threads too.
  CHECK(sg_json["geometric"]["optimizer"]["seed"] == 1);
  CHECK(sg_json["geometric"]["optimizer"]["threads"] == 2);
  const Json threads{{"pose_graph", {{"threads", 7}}},
                     {"geometric", {{"optimizer", {{"threads", 3}}}}}};
  const TrainConfig more = resolve_config("sg-nlf", "smoke", threads);
  CHECK(train_config_to_json(more)["pose_graph"]["threads"] == 7);
  CHECK(train_config_to_json(more)["geometric"]["optimizer"]["threads"] == 3);
  CHECK(more.hash() == sg.hash());
  const TrainConfig seeded =
      resolve_config("geonlf", "smoke", Json{{"geometric", {{"optimizer", {{"seed", 5}}}}}});
  CHECK(seeded.pose_free->geometric->optimizer.seed == 5);
  CHECK(seeded.hash() != resolve_config("geonlf", "smoke").hash());
  CHECK(train_config_from_json(train_config_to_json(seeded), "rt").hash() == seeded.hash());
  CHECK(error_of([] {
          resolve_config("geonlf", "smoke", Json{{"geometric", {{"optimizer", {{"threads", 0}}}}}});
        }).find("threads") != std::string::npos);
}

TEST_CASE("the field lists describe, read, write and range-check each section",
          "[pipeline][config]") {
  const Json schema = train_config_schema();
  // Every section is in SG-NLF's config but LiDAR4D's, which is in its own method's.
  auto method_of = [](const std::string& section) {
    return section == "lidar4d" ? "lidar4d" : "sg-nlf";
  };
  const Json written_sgnlf = train_config_to_json(resolve_config("sg-nlf", "smoke"));
  const Json written_lidar4d = train_config_to_json(resolve_config("lidar4d", "smoke"));
  const Json& written = written_sgnlf;
  const TrainConfig defaults;
  CHECK(schema["optim"]["lr"]["default"] == defaults.optim.lr);
  CHECK(schema["schedule"]["iterations"]["min"] == 1);
  CHECK(schema["schedule"]["patches_on_even_epochs"]["type"] == "boolean");
  CHECK(schema["spectral"]["psi"]["type"] == "object");
  // An optional section is described with its keys under "fields".
  auto keys_of = [](const Json& d) -> const Json& { return d.contains("fields") ? d["fields"] : d; };
  for (const auto& entry : schema.items()) {
    const std::string section = entry.key();
    const Json& keys = keys_of(entry.value());
    CAPTURE(section);
    if (keys.contains("type")) {  // a top-level key, not a section
      CHECK(written.contains(section));
      continue;
    }
    const Json& in = section == "lidar4d" ? written_lidar4d : written_sgnlf;
    REQUIRE(in.contains(section));
    for (const auto& field : keys.items()) {
      const std::string key = field.key();
      const Json& d = field.value();
      CAPTURE(key);
      // Every described key is written (keys added later: only when not their old value), but
      // the optional sections no smoke preset has (on when present).
      const bool absent_optional = section == "geometric" && (key == "reseed" || key == "refine");
      if (absent_optional) CHECK_FALSE(in[section].contains(key));
      else if (!d.contains("written")) CHECK(in[section].contains(key));
      if (!d.contains("max")) continue;
      // Every range is enforced, naming the section and the key.
      const Json too_big = d["max"].is_number_integer() ? Json(d["max"].get<long long>() * 2 + 1)
                                                        : Json(d["max"].get<double>() * 2 + 1);
      const std::string e =
          error_of([&] { resolve_config(method_of(section), "smoke", Json{{section, {{key, too_big}}}}); });
      CHECK(e.find("." + section) != std::string::npos);
      CHECK(e.find("'" + key + "'") != std::string::npos);
    }
  }
  // ... and every key written for these sections is described (pose_graph's own keys only: the
  // confidence graph's are posegraph's).
  CHECK(schema["geometric"]["fields"]["optimizer"]["threads"]["max"] == 256);
  CHECK(schema["field"]["grid"]["half_table"]["default"] == false);
  CHECK(schema["optim"]["adam"]["eps"]["max"] == 1.0);
  for (const char* section : {"field", "optim", "schedule", "spectral", "consistency", "poses",
                              "pose_optim", "reweight", "geometric"})
    for (const auto& field : written[section].items()) {
      CAPTURE(section, field.key());
      CHECK(keys_of(schema[section]).contains(field.key()));
    }
}

TEST_CASE("learning rate decays exponentially to final_factor", "[pipeline][config]") {
  OptimConfig o;
  o.lr = 0.01;
  o.final_factor = 0.1;
  CHECK(o.lr_at(0, 1000) == Approx(0.01));
  CHECK(o.lr_at(500, 1000) == Approx(0.01 * std::sqrt(0.1)));
  CHECK(o.lr_at(1000, 1000) == Approx(0.001));
}

TEST_CASE("the schema describes render, the confidence graph and the nested configs",
          "[pipeline][config]") {
  const Json schema = train_config_schema();
  const Json written = train_config_to_json(resolve_config("sg-nlf", "smoke"));
  CHECK(schema["render"]["n_samples"]["min"] == 1);
  CHECK(schema["render"]["eval_depth"]["written"] == "only when not the default");
  CHECK(schema["render"]["weights"]["grad"]["type"] == "number");
  CHECK(schema["pose_graph"]["kappa"]["default"] == posegraph::ConfidenceGraphConfig{}.kappa);
  CHECK(schema["pose_graph"]["threads"]["max"] == 256);
  CHECK(schema["pose_graph"]["start_epoch"]["min"] == 1);
  CHECK(schema["spectral"]["psi"]["fields"]["activation"]["one_of"].size() == 5);
  CHECK(schema["spectral"]["loss"]["fields"]["form"]["default"] == "ky_fan");
  CHECK(schema["consistency"]["discriminator"]["fields"]["scales"]["max"] == 3);
  // Every key written in these sections is described.
  for (const char* section : {"render", "pose_graph"})
    for (const auto& field : written[section].items()) {
      CAPTURE(section, field.key());
      CHECK(schema[section].contains(field.key()));
    }
  for (const auto& field : written["render"]["weights"].items()) {
    CAPTURE(field.key());
    CHECK(schema["render"]["weights"].contains(field.key()));
  }
}

TEST_CASE("config: the annealed runs' steps per call and the discriminator's weight decay are keys",
          "[config]") {
  const TrainConfig plain = resolve_config("sg-nlf", "quick");
  CHECK(plain.pose_free->geometric->per_call == 10);
  CHECK(plain.consistency->discriminator.weight_decay == 0.0f);
  // Written only when not the values every committed run used, so their hashes stay.
  const Json w = train_config_to_json(plain);
  CHECK_FALSE(w["geometric"].contains("per_call"));
  CHECK_FALSE(w["consistency"]["discriminator"].contains("weight_decay"));
  const TrainConfig c = resolve_config(
      "sg-nlf", "quick",
      Json{{"geometric", {{"per_call", 5}}},
           {"consistency", {{"discriminator", {{"weight_decay", 1e-4}}}}}});
  CHECK(c.pose_free->geometric->per_call == 5);
  CHECK(c.consistency->discriminator.weight_decay == Approx(1e-4));
  CHECK(c.hash() != plain.hash());
  CHECK_THAT(error_of([] {
               resolve_config("sg-nlf", "quick", Json{{"geometric", {{"per_call", 0}}}});
             }),
             Catch::Contains("per_call"));
}
