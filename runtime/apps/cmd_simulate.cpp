// `sgnlf simulate --sequence <name> [--preset P] [--frequency standard|low] [--seed N] --out DIR`
// writes a synthetic sequence in the KITTI-360-like layout; `--list` prints the named sequences.
// --frames / --width / --height shrink it for quick runs.
#include <cstdio>
#include <iostream>

#include "apps/command.hpp"
#include "core/config.hpp"
#include "core/error.hpp"
#include "datasets/simulate.hpp"

namespace sgnlf::app {
namespace {

const Registrar reg("simulate", "Generate a synthetic LiDAR sequence (urban street twin)", [](CLI::App& sub) {
  auto o = std::make_shared<SimOptions>();
  auto out = std::make_shared<std::string>();
  auto list = std::make_shared<bool>(false);
  auto no_noise = std::make_shared<bool>(false);
  sub.add_flag("--list", *list, "Print the named sequences and exit");
  auto list_json = std::make_shared<bool>(false);
  sub.add_flag("--json", *list_json, "With --list: print JSON (the content of datasets/sequences.json)");
  sub.add_option("--sequence", o->sequence, "Named sequence (see --list)");
  sub.add_option("--preset", o->preset, "Sensor preset: kitti360 | nuscenes (default: the sequence's)");
  sub.add_option("--sensor", o->sensor_json, "User-defined sensor JSON (overrides the preset)");
  sub.add_option("--frequency", o->frequency, "standard | low (default: the sequence's)");
  sub.add_option("--seed", o->seed, "World and noise seed");
  sub.add_option("--out", *out, "Output directory");
  sub.add_option("--frames", o->frames, "Number of frames (default 64 standard, 36 low)");
  sub.add_option("--width", o->width, "Override the sensor width (azimuth bins)");
  sub.add_option("--height", o->height, "Override the sensor height (beams)");
  sub.add_option("--moving-vehicles", o->moving_vehicles, "Number of moving vehicles (default: the sequence's)");
  sub.add_option("--threads", o->threads, "Ray-casting threads (0 = all cores; output is identical)");
  sub.add_flag("--no-noise", *no_noise, "Exact ranges and intensities, no random drop");
  sub.add_flag("--motion-distortion", o->realism.motion_distortion,
               "Points timed by azimuth over the sweep, cast from the moving sensor (uncompensated)");
  sub.add_flag("--real-drop", o->realism.real_drop, "Real-scan ray drop: weak lasers, dark surfaces, bursts, far returns");
  sub.add_option("--pedestrians", o->realism.pedestrians, "People walking on the sidewalks");
  sub.add_flag("--vegetation", o->realism.vegetation, "Hedges and bushes along the sidewalks");
  sub.add_option("--beams", o->lidar.beams, "native (the sensor's lasers and azimuth steps) | grid (one ray per pixel)");
  return std::function<int()>([=] {
    if (*list && *list_json) {
      std::cout << named_sequences_json().dump(2) << "\n";
      return 0;
    }
    if (*list) {
      std::printf("%-22s %-9s %-9s %-6s %6s %7s  %s\n", "name", "preset", "frequency", "layout", "frames", "movers", "description");
      for (const auto& s : named_sequences())
        std::printf("%-22s %-9s %-9s %-6s %6d %7d  %s\n", s.name.c_str(), s.preset.c_str(), s.frequency.c_str(),
                    s.layout.c_str(), s.frames, s.moving_vehicles, s.description.c_str());
      return 0;
    }
    if (out->empty()) throw ConfigError("simulate: --out DIR is required");
    if (*no_noise) o->lidar.noise = false;
    const SimResult r = simulate(*o);
    write_synthetic(r, *out);
    const auto& rd = r.metadata["ray_drop"];
    const double rays = rd["rays"].get<double>();
    auto frac = [&](const char* k) { return rd[k].get<double>() / rays; };
    std::printf("wrote %s: %zu frames, %dx%d range images (%s, %s, stride %d, %s beams)\n"
                "  range-image drop rate %.4f; per ray: drop %.4f = no hit %.4f + ego car %.4f + out of range %.4f"
                " + grazing %.4f + weak %.4f + specular %.4f + random %.4f",
                out->c_str(), r.dataset.frames.size(), r.dataset.sensor.height, r.dataset.sensor.width,
                r.dataset.sensor.name.c_str(), r.dataset.frequency.c_str(), r.metadata["stride"].get<int>(),
                o->lidar.beams.c_str(), rd["image_drop_rate"].get<double>(), rd["drop_rate"].get<double>(),
                frac("no_hit"), frac("ego"), frac("out_of_range"), frac("grazing"), frac("weak"), frac("specular"),
                frac("random"));
    if (rd.contains("dark"))
      std::printf(" + dark %.4f + burst %.4f + far %.4f", frac("dark"), frac("burst"), frac("far"));
    std::printf("\n");
    return 0;
  });
});

}  // namespace
}  // namespace sgnlf::app
