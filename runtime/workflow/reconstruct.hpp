// `sgnlf reconstruct`: from a folder of scans to poses, a field, its evaluation and a report, in
// one resumable job (the stages, in order; RUN is the training's run folder, so `sgnlf eval`,
// `render` and `report` work on it too):
//   1. odometry  the built-in LiDAR odometry on the scans (first scan at the identity):
//                RUN/odometry/odometry.{kitti,tum}.txt and odometry.json (per-scan registration)
//   2. train     the pose-free method (sg-nlf, preset quick by default) started from those
//                poses (poses.init = "odometry"): run.json, checkpoints, summary.json,
//                trajectories/ (initial = the odometry, optimised)
//   3. evaluate  the held-out scans (the protocol split of the folder's frame count and rate)
//                against the views rendered at their optimised poses, with the protocol's
//                renderer: RUN/metrics.json (the naive baseline moves the training scans with
//                the same poses when there is no reference)
//   4. anatomy   the evaluated views' errors by cause and band beside the nearest scan's
//                (pipeline/run/anatomy_run.hpp, docs/anatomy.md): RUN/anatomy.json, RUN/anatomy/
//   5. render    the held-out views beside the observed scans (fast renderer): RUN/renders/
//   6. cloud     every scan in the world frame under the optimised poses: RUN/scene.ply and
//                RUN/scene.pcd (binary; x y z intensity float32, world = the first scan's frame)
//   7. report    RUN/report.html (report/report.hpp)
// RUN/reconstruct.json records the request and each finished stage; a rerun with the same
// request skips them (the training resumes from its checkpoint), another request is refused.
// Pose errors (ATE/RPE, protocol §4) are reported only against reference poses: a layout that
// has them, or `reference_poses` (a KITTI poses file, line k = scan file k in name order).
#pragma once
#include <cstdint>
#include <string>

#include "cl/runtime.hpp"
#include "core/config_fwd.hpp"
#include "datasets/loader.hpp"

namespace sgnlf::workflow {

struct ReconstructRequest {
  std::string scans;    // a folder of scans (or any layout load_dataset reads)
  std::string run_dir;
  std::string method = "sg-nlf";  // a pose-free method
  std::string preset = "quick";
  std::string config;   // JSON file of config overrides ("" none)
  std::string device;   // recorded in run.json
  uint64_t seed = 1;
  LoadOptions load;     // frames -1 on a plain folder: every scan
  std::string reference_poses;
  bool show_progress = true;

  // The request as recorded in reconstruct.json (what must match on resume: not the device,
  // the reference poses, which only score the result, or the progress display). The scans
  // folder is recorded as an absolute, normal path: naming it relatively, or with a trailing
  // '/', on a later run is the same request.
  Json to_json() const;
};

inline constexpr const char* kReconstructStages[] = {"odometry", "train", "evaluate", "anatomy",
                                                    "render",   "cloud", "report"};

// Runs (or resumes) the job; returns the contents of RUN/reconstruct.json. ConfigError for a
// method that is not pose-free, a bad config or a request that differs from the folder's;
// IoError for unreadable scans or reference poses; Error when a scan does not register.
Json reconstruct(cl::Runtime& rt, const ReconstructRequest& req);

}  // namespace sgnlf::workflow
