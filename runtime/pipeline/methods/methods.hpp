// One function per method file of this folder, returning its description (method.hpp); the
// registry (registry.cpp) lists them and the variants derive from their base's.
#pragma once
#include "pipeline/methods/method.hpp"

namespace sgnlf::pipeline::methods {

Method lidar_nerf();             // lidar_nerf.cpp
Method lidar4d();                // lidar4d.cpp
Method geonlf();                 // geonlf.cpp
Method geonlf_frozen();          // geonlf_frozen.cpp
Method sg_nlf();                 // sg_nlf.cpp
Method sg_nlf_no_consistency();  // sg_nlf_no_consistency.cpp
Method sg_nlf_no_hybrid();       // sg_nlf_no_hybrid.cpp
Method sg_nlf_spectral_only();   // sg_nlf_spectral_only.cpp
Method sg_nlf_no_graph();        // sg_nlf_no_graph.cpp
Method sg_nlf_baseline();        // sg_nlf_baseline.cpp
Method sg_nlf_gt_poses();        // sg_nlf_gt_poses.cpp

}  // namespace sgnlf::pipeline::methods
