// simulate(): a named sequence's street, drive and scans (see simulate.hpp).
#include "datasets/simulate.hpp"

#include <cmath>
#include <algorithm>

#include "core/config.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "core/progress.hpp"
#include "datasets/protocol.hpp"
#include "datasets/sim_street.hpp"
#include "datasets/sim_sweep.hpp"

namespace sgnlf {

namespace {
// The real-scan ray-drop causes of the real-like twins, set so that the simulated range images
// drop about what the real ones do (datasets/README.md "Real-like twins": nuScenes scene-0916
// drops 0.29 of its 32 × 1080 pixels, KITTI 0.28 of 66 × 1030).
void apply_real_drop(sim::LidarModel& m, bool nuscenes) {
  m.burst_columns = 12;
  if (nuscenes) {
    m.beam_gain_sigma = 0.5;
    m.dark_drop = 0.25;
    m.burst_drop = 0.01;
    m.ego_top_m = 0.7;  // the lowest lasers of the real LIDAR_TOP see the car's roof
  } else {  // real KITTI loses more in every row, and its lowest rows see the car
    m.beam_gain_sigma = 0.8;
    m.dark_drop = 0.6;
    m.burst_drop = 0.02;
    m.ego_top_m = 0.6;
  }
}

SimRealism resolve_realism(const SimRealism& seq, const SimRealism& opt) {
  SimRealism r = seq;
  r.motion_distortion = r.motion_distortion || opt.motion_distortion;
  r.pedestrians = std::max(r.pedestrians, opt.pedestrians);
  r.vegetation = r.vegetation || opt.vegetation;
  r.real_drop = r.real_drop || opt.real_drop;
  r.extra_setback_m = std::max(r.extra_setback_m, opt.extra_setback_m);
  return r;
}
}  // namespace

void SimOptions::validate() const {
  find_sequence(sequence);
  if (!frequency.empty() && frequency != "standard" && frequency != "low")
    throw ConfigError("simulate: frequency '" + frequency + "' (expected standard or low)");
  if (frames == 0 || frames < -1 || frames > 100000) throw ConfigError("simulate: frames = " + std::to_string(frames));
  if (width == 0 || width < -1) throw ConfigError("simulate: width = " + std::to_string(width));
  if (height == 0 || height < -1) throw ConfigError("simulate: height = " + std::to_string(height));
  if (realism.pedestrians < 0 || realism.pedestrians > 10000)
    throw ConfigError("simulate: pedestrians = " + std::to_string(realism.pedestrians));
  check_range("simulate", "extra_setback_m", realism.extra_setback_m, 0.0, 100.0);
  actors.validate();
  lidar.validate();
}

SimResult simulate(const SimOptions& opt) {
  opt.validate();
  const NamedSequence& ns = find_sequence(opt.sequence);
  const std::string preset = opt.preset.empty() ? ns.preset : opt.preset;
  Sensor sensor = opt.sensor_json.empty() ? sensor_preset(preset)
                                          : sensor_from_json(load_json_file(opt.sensor_json), opt.sensor_json);
  if (opt.width > 0) sensor.width = opt.width;
  if (opt.height > 0) sensor.height = opt.height;
  sensor.validate();
  const std::string freq = opt.frequency.empty() ? ns.frequency : opt.frequency;
  const int n = opt.frames > 0 ? opt.frames : freq == ns.frequency ? ns.frames : (freq == "low" ? 36 : 64);
  const int stride = freq == "low" ? std::max(1, int(std::lround(sensor.rate_hz / 2.0))) : 1;  // 2 Hz
  const int movers = opt.moving_vehicles >= 0 ? opt.moving_vehicles : ns.moving_vehicles;
  const uint64_t world_seed = fnv1a64(ns.name + "#" + std::to_string(opt.seed));
  const bool nus = preset == "nuscenes";

  sim::DriveConfig dc;
  dc.seed = world_seed;
  dc.v_min = nus ? 3.0 : 5.0;
  dc.v_max = nus ? 8.0 : 10.0;
  if (ns.layout == "loop") { dc.v_min = 10.0; dc.v_max = 12.0; }  // around the block and back
  dc.sensor_height_m = nus ? 1.84 : 1.73;
  std::vector<double> times;
  std::vector<int> ids;
  for (int k = 0; k < n; ++k) {
    ids.push_back(k * stride);
    times.push_back(k * stride / sensor.rate_hz);
  }
  const SimRealism realism = resolve_realism(ns.realism, opt.realism);
  sim::LidarModel lidar = opt.lidar;
  if (nus) lidar.intensity_gain *= 0.3;  // real nuScenes LIDAR_TOP: mean intensity 0.074 after / 255
  if (realism.real_drop) apply_real_drop(lidar, nus);
  sim::StreetConfig sc;
  sc.layout = ns.layout;
  sc.seed = world_seed;
  sc.moving_vehicles = movers;
  sc.pedestrians = realism.pedestrians;
  sc.vegetation = realism.vegetation;
  sc.extra_setback_m = realism.extra_setback_m;
  sc.drive_length_m = times.back() * dc.v_max + 10.0;
  sim::StreetWorld world = sim::generate_street(sc);
  // With motion distortion the drive is sampled at each sweep's start and end (the world's clock
  // runs one sweep ahead of the frames' timestamps, so that the first sweep starts at t ≥ 0).
  const double sweep_s = sensor.sweep_duration_s(), clock = realism.motion_distortion ? sweep_s : 0.0;
  std::vector<double> drive_times;
  for (double t : times) {
    if (!realism.motion_distortion) { drive_times.push_back(t); continue; }
    const double start = t + clock - sensor.sweep.reference * sweep_s;
    drive_times.push_back(start);
    drive_times.push_back(start + sweep_s);
  }
  const auto poses = sim::drive(world, dc, drive_times);
  // Moving actors on the world clock: each frame's reference moment is its timestamp + clock.
  const sim::ActorsConfig actor_cfg = opt.actors.any() ? opt.actors : ns.actors;
  std::vector<sim::ActorTrack> actors;
  if (actor_cfg.any()) {
    std::vector<double> world_times;
    std::vector<Pose> ego;
    for (int k = 0; k < n; ++k) {
      world_times.push_back(times[size_t(k)] + clock);
      ego.push_back(realism.motion_distortion
                        ? sim::SweepPoses{poses[2 * size_t(k)], poses[2 * size_t(k) + 1]}.at(sensor.sweep.reference)
                        : poses[size_t(k)]);
    }
    actors = sim::generate_actors(actor_cfg, world, world_times, ego, dc.v_max, world_seed);
  }
  auto place_all = [&](double t_world) {
    world.place_movers(t_world);
    sim::place_actors(world.scene, actors, t_world);
  };

  SimResult res;
  Dataset& d = res.dataset;
  d.name = ns.name;
  d.source = "synthetic";
  d.frequency = freq;
  d.sensor = sensor;
  Progress prog("simulate " + ns.name, n);
  std::vector<Json> per_frame;
  double image_drop = 0;
  for (int k = 0; k < n; ++k) {
    Frame f;
    f.id = ids[size_t(k)];
    f.timestamp_s = times[size_t(k)];
    sim::DropStats st;
    Json sweep_json;
    std::vector<uint16_t> labels;
    std::vector<uint16_t>* want_labels = actors.empty() ? nullptr : &labels;
    if (realism.motion_distortion) {
      const sim::SweepPoses sp{poses[2 * size_t(k)], poses[2 * size_t(k) + 1]};
      const double start = drive_times[2 * size_t(k)];
      f.T_world_lidar = sp.at(sensor.sweep.reference);
      f.points = sim::cast_sweep(world.scene, sensor, sp, lidar, world_seed, uint32_t(f.id), opt.threads, &st,
                                 [&](double fraction) { place_all(start + fraction * sweep_s); }, 72, want_labels);
      res.sweeps.push_back(sp);
      const Vec6 xi = sp.twist_per_s(sweep_s);
      sweep_json = Json::array({xi[0], xi[1], xi[2], xi[3], xi[4], xi[5]});
    } else {
      place_all(times[size_t(k)]);
      f.T_world_lidar = poses[size_t(k)];
      f.points = sim::cast_scan(world.scene, sensor, f.T_world_lidar, lidar, world_seed, uint32_t(f.id),
                                opt.threads, &st, want_labels);
    }
    size_t actor_returns = 0;
    if (!actors.empty()) {
      for (const auto& a : actors) f.actors.push_back(a.box(f.timestamp_s + clock, world.scene.ground_z));
      for (uint16_t l : labels) actor_returns += l != 0;
      f.labels = std::move(labels);
    }
    ProjectionStats ps;
    f.image = project_points(sensor, f.points, &ps);
    res.drops.add(st);
    const double img_drop = 1.0 - double(ps.projected) / double(f.image.size());
    image_drop += img_drop / n;
    per_frame.push_back(Json{{"frame", f.id}, {"points", f.points.size()}, {"ray_drop_rate", st.drop_rate()},
                             {"image_drop_rate", img_drop}});
    if (!sweep_json.is_null()) per_frame.back()["sweep_twist_per_s"] = sweep_json;
    if (!actors.empty()) per_frame.back()["actor_returns"] = actor_returns;
    d.frames.push_back(std::move(f));
    prog.update(k + 1);
  }
  prog.finish();
  // A sequence's own split applies at its own frequency (--frequency low: the protocol's).
  const std::string split = freq == ns.frequency ? ns.split : "protocol";
  d.split = named_split(split, n, freq);
  const auto& D = res.drops;
  res.metadata = Json{
      {"format", "sgnlf-synthetic"}, {"version", 1}, {"name", ns.name}, {"sequence", ns.name + "_sync"},
      {"preset", preset}, {"frequency", freq}, {"layout", ns.layout}, {"seed", opt.seed},
      {"world_seed", hex64(world_seed)}, {"first_frame", 0}, {"stride", stride}, {"frames", n},
      {"moving_vehicles", movers}, {"description", ns.description},
      {"scene", {{"primitives", world.scene.primitives().size()}, {"road_half_width_m", world.road_half_width},
                 {"sidewalk_width_m", world.sidewalk_width}, {"path_length_m", world.path.length()},
                 {"closed_path", world.path.closed}}},
      {"beams", opt.lidar.beams},
      {"ray_drop", {{"image_drop_rate", image_drop}, {"rays", D.rays}, {"returns", D.returns}, {"drop_rate", D.drop_rate()}, {"ego", D.ego},
                    {"no_hit", D.no_hit}, {"out_of_range", D.out_of_range}, {"grazing", D.grazing},
                    {"weak", D.weak}, {"specular", D.specular}, {"random", D.random}}},
      {"per_frame", per_frame}};
  if (realism.any()) {  // only then: the metadata of the other sequences stays as it was
    res.metadata["realism"] = realism.to_json();
    res.metadata["sweep"] = Json{{"duration_s", sweep_s}, {"timing", sweep_timing_to_json(sensor.sweep)}};
    auto& rd = res.metadata["ray_drop"];
    rd["dark"] = D.dark;
    rd["burst"] = D.burst;
    rd["far"] = D.far;
  }
  // Only with them: the metadata of the other sequences stays as it was.
  if (split != "protocol") {
    Json ids = Json::array();
    for (int i : d.split.test) ids.push_back(d.frames[size_t(i)].id);
    res.metadata["split"] = split;
    res.metadata["test_frame_ids"] = ids;
  }
  if (!actors.empty()) {
    res.metadata["actors"] = actor_cfg.to_json();
    res.metadata["actors"]["count"] = actors.size();
    res.metadata["actors"]["clock_offset_s"] = clock;
    res.actors = actors;
    res.actor_clock_offset_s = clock;
  }
  log::info("simulated ", ns.name, ": ", n, " frames, ", D.rays, " rays, ray drop rate ", D.drop_rate(),
            ", range-image drop rate ", image_drop);
  return res;
}

Dataset simulate_dataset(const SimOptions& opt) { return simulate(opt).dataset; }

}  // namespace sgnlf
