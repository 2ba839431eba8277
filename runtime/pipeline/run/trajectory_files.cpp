// write_run_trajectories (see trajectory_files.hpp).
#include "pipeline/run/trajectory_files.hpp"

#include <filesystem>

#include "core/error.hpp"
#include "datasets/protocol.hpp"
#include "io/trajectory_io.hpp"
#include "io/trajectory_svg.hpp"

namespace sgnlf::pipeline {
namespace fs = std::filesystem;

std::string write_run_trajectories(const std::string& run_dir, const Dataset& d,
                                   const std::vector<Pose>& init, const std::vector<Pose>& opt) {
  require(init.size() == d.frames.size() && opt.size() == d.frames.size(),
          "write_run_trajectories: pose counts differ from the " + std::to_string(d.frames.size()) +
              " frames");
  const fs::path dir = fs::path(run_dir) / "trajectories";
  fs::create_directories(dir);
  std::vector<double> ts;
  for (const auto& f : d.frames) ts.push_back(f.timestamp_s);
  // Scans without reference poses have no "gt" files: their identity poses are no reference.
  const std::vector<Pose> gt = gt_poses(d);
  std::vector<std::pair<const char*, const std::vector<Pose>*>> sets = {{"initial", &init},
                                                                        {"optimised", &opt}};
  if (d.has_reference_poses) sets.insert(sets.begin(), {"gt", &gt});
  for (const auto& [name, poses] : sets) {
    io::write_kitti_poses((dir / (std::string(name) + ".kitti.txt")).string(), *poses);
    io::write_tum_poses((dir / (std::string(name) + ".tum.txt")).string(), ts, *poses);
  }
  std::vector<io::SvgTrajectory> lines = {{"initial", "#e6842a", init}, {"optimised", "#1f77b4", opt}};
  std::vector<std::pair<int, int>> links = {{1, 0}};
  if (d.has_reference_poses) {
    lines.insert(lines.begin(), {"ground truth", "#000000", gt});
    links = {{2, 0}};
  }
  io::write_trajectory_svg((dir / "top_view.svg").string(), d.name + ": poses from above (metres, not aligned)",
                           lines, links);
  return dir.string();
}

}  // namespace sgnlf::pipeline
