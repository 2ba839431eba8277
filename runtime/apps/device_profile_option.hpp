// `--device-profile cpu|gpu|auto|FILE`, beside `--device` on every command that opens an OpenCL
// runtime (train, eval, render, anatomy, reconstruct, bench, spectral, devices): the launch shapes and
// kernel variants (cl/device_profile.hpp); default $SGNLF_DEVICE_PROFILE, else auto (cpu on CPU
// devices, gpu on the others). A bad name or file fails when the runtime opens (exit 2).
#pragma once
#include <string>

#include "apps/command.hpp"

namespace sgnlf::app {

inline void add_device_profile_option(CLI::App& sub, std::string& spec) {
  sub.add_option("--device-profile", spec,
                 "Device profile: cpu, gpu, auto or a JSON profile file (launch shapes and the "
                 "encoders' backward variant; default $SGNLF_DEVICE_PROFILE, else auto: cpu on "
                 "CPU devices, gpu on others; recorded in the results' context)");
}

}  // namespace sgnlf::app
