// `sgnlf render --run <run dir> [--out <dir>] [--data <dataset>] [--device SPEC] [--poses FILE]`:
// renders the test frames of a trained run (npy arrays and PNGs of the rendering above the
// ground truth), or novel views at the poses of a KITTI-format trajectory file.
#include <filesystem>
#include <iostream>

#include "apps/command.hpp"
#include "io/trajectory_io.hpp"
#include "pipeline/run/session.hpp"

namespace sgnlf::app {
namespace {

struct RenderArgs {
  std::string run, out, data, device, poses;
  pipeline::RenderSampling sampling;
};

const Registrar reg("render", "Render the test frames of a trained run", [](CLI::App& sub) {
  auto a = std::make_shared<RenderArgs>();
  sub.add_option("--run", a->run, "Run folder")->required();
  sub.add_option("--out", a->out, "Output folder (default <run>/renders)");
  sub.add_option("--data", a->data, "Dataset folder (default: the one the run trained on)");
  sub.add_option("--device", a->device, "OpenCL device index or name substring");
  sub.add_option("--poses", a->poses,
                 "Render these views instead of the test frames: KITTI trajectory file, one "
                 "T_world_lidar per line (12 numbers, the dataset's world frame, metres)");
  sub.add_option("--samples", a->sampling.n_samples,
                 "Uniform samples per ray when rendering (default: the config's render.eval_samples, else as trained)");
  sub.add_option("--importance", a->sampling.n_importance,
                 "Importance samples per ray when rendering (default: the config's render.eval_importance, else as trained)");
  sub.add_option("--depth", a->sampling.depth,
                 "Rendered depth: expected (sum of w_i t_i, as trained and published) or median "
                 "(where the accumulated weight reaches 1/2; a diagnostic). Default: the config's "
                 "render.eval_depth, else expected")
      ->check(CLI::IsMember({"expected", "median"}));
  return std::function<int()>([a] {
    // Poses first: a bad trajectory file fails before the run is loaded.
    const std::vector<Pose> poses =
        a->poses.empty() ? std::vector<Pose>{} : io::read_kitti_poses(a->poses);
    cl::Runtime rt(a->device);
    auto run = pipeline::load_run(rt, a->run, a->data, a->sampling);
    const std::string out =
        a->out.empty() ? (std::filesystem::path(a->run) / "renders").string() : a->out;
    const Json files = a->poses.empty()
                           ? pipeline::render_run(run, out)
                           : pipeline::render_poses(run, poses, out);
    std::cout << files.dump(2) << "\n";
    return 0;
  });
});

}  // namespace
}  // namespace sgnlf::app
