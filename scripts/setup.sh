#!/usr/bin/env bash
# Installs every build and run dependency of sgnlf from Debian packages. Idempotent; works as
# root or through sudo. Skips apt entirely when everything is already installed.
set -euo pipefail
PACKAGES=(
  build-essential cmake pkg-config git
  pocl-opencl-icd ocl-icd-libopencl1 ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers clinfo
  libeigen3-dev nlohmann-json3-dev catch2 libbenchmark-dev libcli11-dev libstb-dev libpng-dev
)
# The fuzz targets and CI's sanitizer job build with clang and its libFuzzer runtime.
if [ "${SGNLF_SETUP_CLANG:-0}" = "1" ]; then PACKAGES+=(clang libclang-rt-dev); fi
# The test job opens the `sgnlf report` page in headless Chromium (tests/report/test_browser.cpp;
# without it that test warns and passes). run.sh does not need it.
if [ "${SGNLF_SETUP_BROWSER:-0}" = "1" ]; then PACKAGES+=(chromium); fi
# The test job's Oclgrind tests (CTest label oclgrind, tests/oclgrind/) run the device tests under
# Debian's OpenCL device simulator. The package registers no ICD: other programs keep PoCL.
if [ "${SGNLF_SETUP_OCLGRIND:-0}" = "1" ]; then PACKAGES+=(oclgrind); fi
# The test job's scale-out tests (harness_scale_out_{slurm,parallel}, tests/harness/scale_out.sh)
# run the README's Slurm and GNU parallel lines; the Slurm one starts its own munged, slurmctld
# and slurmd in a temporary folder. The packages' own services stay off where no slurm.conf is in
# /etc/slurm (systemd starts munge with the key Debian makes; a container starts nothing).
if [ "${SGNLF_SETUP_SCALE_OUT:-0}" = "1" ]; then PACKAGES+=(slurm-wlm munge parallel); fi
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PACKAGES[@]} packages present"
  exit 0
fi
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "setup: installing ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
