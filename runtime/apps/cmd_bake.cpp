// `sgnlf bake RUN --out SCENE [--ply FILE] [--voxel M] [--brick N] [--dilate M] [--config FILE]
// [--device SPEC]`: bakes a trained run's static field into a sparse brick scene (docs/baking.md)
// that `sgnlf render --baked SCENE` ray-casts; optionally its surface as a PLY mesh with
// intensity and ray-drop attributes. Prints the bake's time and memory.
#include <chrono>
#include <iostream>

#include "apps/command.hpp"
#include "apps/device_profile_option.hpp"
#include "bake/surface_mesh.hpp"
#include "core/config.hpp"
#include "pipeline/run/bake_run.hpp"

namespace sgnlf::app {
namespace {

struct BakeArgs {
  std::string run, out, ply, config, data, device, device_profile;
  float voxel_m = 0.0f, dilate_m = -1.0f;
  int brick = 0;
};

const Registrar reg("bake", "Bake a trained run's field into a scene for the ray caster", [](CLI::App& sub) {
  auto a = std::make_shared<BakeArgs>();
  sub.add_option("run", a->run, "Run folder (a static field: LiDAR-NeRF, GeoNLF, SG-NLF)")->required();
  sub.add_option("--out", a->out, "Baked scene file to write (render --baked reads it)")->required();
  sub.add_option("--ply", a->ply,
                 "Also write the baked surface as a binary PLY mesh (vertex x y z intensity "
                 "drop_probability, triangle faces; world metres)");
  sub.add_option("--config", a->config, "JSON of the bake's settings (keys of bake/bake_config.hpp)");
  sub.add_option("--voxel", a->voxel_m, "Voxel size, metres (default 0.1)");
  sub.add_option("--brick", a->brick, "Cells per brick side (default 8)");
  sub.add_option("--dilate", a->dilate_m, "Bricks kept within this distance of a training return, metres (default 0.3)");
  sub.add_option("--data", a->data, "Dataset folder (default: the one the run trained on)");
  sub.add_option("--device", a->device, "OpenCL device index or name substring");
  add_device_profile_option(sub, a->device_profile);
  return std::function<int()>([a] {
    bake::BakeConfig cfg;
    if (!a->config.empty()) cfg = bake::BakeConfig::from_json(load_config_file(a->config), a->config);
    if (a->voxel_m > 0.0f) cfg.voxel_m = a->voxel_m;
    if (a->brick > 0) cfg.brick = a->brick;
    if (a->dilate_m >= 0.0f) cfg.dilate_m = a->dilate_m;
    cfg.validate("bake options");
    cl::Runtime rt(a->device, a->device_profile);
    const auto t0 = std::chrono::steady_clock::now();
    auto run = pipeline::load_run(rt, a->run, a->data);
    const double load_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    bake::BakeStats st;
    const bake::BakedScene scene = pipeline::bake_run(run, a->run, cfg, &st);
    bake::write_baked_scene(a->out, scene);
    Json summary{{"scene", a->out},
                 {"bricks", scene.bricks()},
                 {"bytes", scene.bytes()},
                 {"mib", double(scene.bytes()) / double(1 << 20)},
                 {"load_s", load_s},
                 {"bake", st.to_json()},
                 {"config", cfg.to_json()}};
    if (!a->ply.empty()) {
      const auto tm = std::chrono::steady_clock::now();
      const bake::SurfaceMesh mesh = bake::extract_surface(scene, bake::surface_level(scene));
      bake::write_surface_ply(a->ply, mesh);
      summary["ply"] = Json{{"file", a->ply},
                            {"vertices", mesh.intensity.size()},
                            {"triangles", mesh.triangles.size()},
                            {"seconds", std::chrono::duration<double>(std::chrono::steady_clock::now() - tm).count()}};
    }
    std::cerr << "bake: " << scene.bricks() << " bricks, " << summary["mib"].get<double>()
              << " MiB, baked in " << st.seconds << " s (" << st.density_seconds << " s density, "
              << st.head_seconds << " s head) after " << load_s << " s loading the run\n";
    std::cout << summary.dump(2) << "\n";
    return 0;
  });
});

}  // namespace
}  // namespace sgnlf::app
