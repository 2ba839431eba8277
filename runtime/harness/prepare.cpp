#include "harness/prepare.hpp"

#include <chrono>
#include <filesystem>

#include "core/config.hpp"
#include "core/log.hpp"
#include "datasets/loader.hpp"
#include "datasets/simulate.hpp"

namespace sgnlf::harness {
namespace fs = std::filesystem;

namespace {

// What the results record about a dataset (results/schema.md "dataset").
Json describe(const Dataset& d, const std::string& dir) {
  Json ids = Json::array();
  for (const auto& f : d.frames) ids.push_back(f.id);
  return Json{{"name", d.name},
              {"source", d.source},
              {"path", dir},
              {"frequency", d.frequency},
              {"frames", d.frames.size()},
              {"frame_ids", ids},
              {"train", d.split.train},
              {"test", d.split.test},
              {"sensor", sensor_to_json(d.sensor)}};
}

}  // namespace

PreparedSequence prepare_sequence(const SequenceDef& s, const BenchOptions& opt,
                                  const std::string& dir) {
  const auto t0 = std::chrono::steady_clock::now();
  PreparedSequence p;
  p.dataset_dir = dir;
  fs::remove_all(dir);
  // --data-root, or <real root>/<real_dir> for a real sequence of a synthetic scale.
  const std::string root = sequence_data_root(s, opt);
  SimResult r;
  if (root.empty()) {
    SimOptions so;
    so.sequence = s.name;
    so.preset = s.preset;
    so.frequency = s.frequency;
    so.seed = kSyntheticDataSeed;
    if (s.frames > 0) so.frames = s.frames;
    if (s.width > 0) so.width = s.width;
    r = simulate(so);
  } else {
    LoadOptions lo;
    lo.sequence = s.sequence;
    lo.frequency = s.frequency;
    lo.start = s.start;
    lo.frames = s.frames > 0 ? s.frames : -1;
    lo.stride = s.stride > 0 ? s.stride : -1;
    r.dataset = load_dataset(root, lo);
    const auto& fr = r.dataset.frames;
    require(!fr.empty(), "bench: " + root + " holds no frames for window " + s.name);
    // Keep the real frame ids when they are evenly spaced; otherwise number them 0..n−1.
    int stride = fr.size() > 1 ? fr[1].id - fr[0].id : 1;
    bool even = stride > 0;
    for (size_t k = 1; k < fr.size(); ++k) even = even && fr[k].id - fr[k - 1].id == stride;
    Json source_ids = Json::array();
    for (auto& f : r.dataset.frames) source_ids.push_back(f.id);
    if (!even) {
      for (size_t k = 0; k < r.dataset.frames.size(); ++k) r.dataset.frames[k].id = int(k);
      stride = 1;
    }
    r.metadata = Json{{"format", "sgnlf-synthetic"}, {"version", 1}, {"name", s.name},
                      {"sequence", s.name + "_sync"}, {"preset", s.preset},
                      {"frequency", r.dataset.frequency}, {"first_frame", r.dataset.frames[0].id},
                      {"stride", stride}, {"frames", r.dataset.frames.size()},
                      {"real_source", r.dataset.source}, {"real_path", root},
                      {"planar_reference", r.dataset.planar_reference},
                      {"real_sequence", s.sequence}, {"source_frame_ids", source_ids},
                      {"description", "window of real data copied by sgnlf bench"}};
  }
  // The table's test frames (SequenceDef::test_frames) replace the sequence's split; the
  // loader reads them back from sgnlf_dataset.json ("test_frame_ids").
  if (!s.test_frames.empty()) {
    const int n = int(r.dataset.frames.size());
    Json ids = Json::array();
    for (int pos : s.test_frames) {
      if (pos >= n)
        throw ConfigError("bench: sequence " + s.name + ": test frame position " + std::to_string(pos) +
                          " but the window holds " + std::to_string(n) + " frames");
      ids.push_back(r.dataset.frames[size_t(pos)].id);
    }
    r.metadata["test_frame_ids"] = ids;
  }
  write_synthetic(r, dir);
  LoadOptions check;
  check.load_points = false;
  const Dataset written = load_dataset(dir, check);
  p.dataset = describe(written, dir);
  p.dataset["generator"] = root.empty() ? Json{{"simulator_seed", kSyntheticDataSeed},
                                               {"world_seed", r.metadata.value("world_seed", "")},
                                               {"ray_drop", r.metadata.value("ray_drop", Json())}}
                                        : Json{{"real_source", r.dataset.source},
                                               {"real_path", root}};
  p.dataset["seed"] = root.empty() ? Json(kSyntheticDataSeed) : Json(nullptr);
  p.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  log::info("[bench] prepared ", s.name, " in ", dir, " (", written.frames.size(), " frames, ",
            p.seconds, " s)");
  return p;
}

}  // namespace sgnlf::harness
