#!/usr/bin/env bash
# One unattended check of the project on an OpenCL device (issue 54, item 7), meant for a GPU
# machine lent for minutes: the OpenCL ICD loader, the build, the device list, the device-vs-
# reference tests of every kernel family, a short set of kernel benchmarks and N paper-scale
# training steps of each method, all on the device SGNLF_DEVICE selects (default: sgnlf's own
# choice, the first GPU) under the device profile SGNLF_DEVICE_PROFILE (default here: gpu).
# Writes ONE JSON, gpu-check.json (device, profile, each part's rc and wall seconds, benchmark
# medians, training rates), and gpu-check-logs.tar.gz (every part's log, the benchmark JSONs,
# the training summaries) into the output folder: $1, else $OUT, else runs/gpu-check.
# Every part runs under its own timeout; a failed part is reported on stderr with its log's
# tail, and the script goes on, then exits 1 if any part failed (the JSON is written anyway).
#
#   bash scripts/gpu-check.sh [OUT_DIR]
#
# Settings (environment):
#   SGNLF_BUILD_DIR=DIR     a prebuilt build folder: no build (default: scripts/build.sh into build/)
#   SGNLF_ICD_DEB=FILE      ocl-icd-libopencl1_*.deb, unpacked into the work folder when
#                           libOpenCL.so.1 is missing (else apt-get, when it is reachable)
#   SGNLF_DEBS=DIR          more .deb files unpacked the same way (a prebuilt build's runtime
#                           libraries, e.g. libbenchmark1debian)
#   SGNLF_DEVICE, SGNLF_DEVICE_PROFILE   the device and its profile (README, "Profile the kernels")
#   SGNLF_GPU_CHECK_STEPS=50            training steps per method (the first N of the schedule)
#   SGNLF_GPU_CHECK_PRESET=paper        training preset
#   SGNLF_GPU_CHECK_METHODS="lidar-nerf lidar4d geonlf sg-nlf"
#   SGNLF_GPU_CHECK_SIM_ARGS=""         extra `sgnlf simulate` options (e.g. "--frames 14 --width 128
#                                       --height 16" for a small dataset; default: the protocol's)
#   SGNLF_GPU_CHECK_BENCH="bin:regex ..."   benchmark binaries and filters (default below)
#   SGNLF_GPU_CHECK_MIN_TIME=0.05       --benchmark_min_time (seconds; benchmarks that set
#                                       their own MinTime keep it)
#   SGNLF_GPU_CHECK_PARTS="icd build devices tests bench train"   the parts to run
#   timeouts in seconds: T_BUILD=300 T_DEVICES=60 T_TEST=120 (per kernel family) T_BENCH=90 (per
#   binary) T_SIM=120 T_TRAIN=120 (per method), each cut to what is left of
#   SGNLF_GPU_CHECK_DEADLINE=480 (seconds from the start; a part with under 5 s left is not run
#   and counts as failed)
# docs/gpu-check.md describes the parts and the JSON.
set -uo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
OUT_DIR=${1:-${OUT:-runs/gpu-check}}
mkdir -p "$OUT_DIR" || { echo "gpu-check: cannot create $OUT_DIR" >&2; exit 2; }
OUT_DIR=$(cd "$OUT_DIR" && pwd)
WORK=$(mktemp -d "${TMPDIR:-/tmp}/sgnlf-gpu-check.XXXXXX")
BUILD=${SGNLF_BUILD_DIR:-build}
case "$BUILD" in /*) ;; *) BUILD=$ROOT/$BUILD ;; esac
STEPS=${SGNLF_GPU_CHECK_STEPS:-50}
PRESET=${SGNLF_GPU_CHECK_PRESET:-paper}
METHODS=${SGNLF_GPU_CHECK_METHODS:-"lidar-nerf lidar4d geonlf sg-nlf"}
SIM_ARGS=${SGNLF_GPU_CHECK_SIM_ARGS:-}
MIN_TIME=${SGNLF_GPU_CHECK_MIN_TIME:-0.05}
PARTS=${SGNLF_GPU_CHECK_PARTS:-"icd build devices tests bench train"}
BENCH=${SGNLF_GPU_CHECK_BENCH:-"bench_roofline:BM_Roofline(Fma|Triad) \
bench_field:BM_HashGridFwd/|BM_HashGridBwdDeterministic/|BM_(HashGrid|TimeHashGrid|KPlanes)BwdVariant|BM_MlpDensityFwd/262144|BM_MlpHeadBwd/262144|BM_MlpGemmHeadBwd/262144/|BM_Adam \
bench_render:BM_SampleUniform|BM_VolumeForward|BM_VolumeBackward|BM_RangeLoss \
bench_conv:BM_ConvGemm(Fwd|BwdIn|BwdWgt)/(patchgan1|unet_up0a)/ \
bench_pipeline:BM_TrainStep/quick/|BM_PoseFreeStep"}
T_BUILD=${T_BUILD:-300} T_DEVICES=${T_DEVICES:-60} T_TEST=${T_TEST:-120}
T_BENCH=${T_BENCH:-90} T_SIM=${T_SIM:-120} T_TRAIN=${T_TRAIN:-120}
DEADLINE=${SGNLF_GPU_CHECK_DEADLINE:-480}
export SGNLF_DEVICE_PROFILE=${SGNLF_DEVICE_PROFILE:-gpu}
PARTS_TSV=$WORK/parts.tsv
: > "$PARTS_TSV"
FAILED=0
T_START=$(date +%s)

say() { echo "gpu-check: $*" >&2; }
want() { case " $PARTS " in *" $1 "*) return 0 ;; *) return 1 ;; esac; }
# record NAME RC SECONDS LOG [NOTE]: one line of parts.tsv (the report reads it).
record() {
  printf '%s\t%s\t%s\t%s\t%s\n' "$1" "$2" "$3" "${4:-}" "${5:-}" | tr -d '\r' >> "$PARTS_TSV"
  if [ "$2" != 0 ] && [ "$2" != skipped ]; then FAILED=1; fi
}
# part NAME TIMEOUT COMMAND...: runs the command under its timeout into logs/NAME.log and
# records its rc (124 = timed out) and wall seconds; a failure prints the log's tail.
part() {
  local name=$1 limit=$2; shift 2
  local log=$WORK/logs/$name.log t0 t1 rc left
  mkdir -p "$WORK/logs"
  left=$((DEADLINE - ($(date +%s) - T_START)))
  if [ "$left" -lt 5 ]; then
    say "$name NOT RUN: the deadline (SGNLF_GPU_CHECK_DEADLINE=${DEADLINE}s) has passed"
    record "$name" deadline 0 "" "not run: past the ${DEADLINE}s deadline"
    return 1
  fi
  [ "$left" -lt "$limit" ] && limit=$left
  say "$name (timeout ${limit}s) ..."
  t0=$(date +%s.%N)
  timeout --kill-after=10 "$limit" "$@" > "$log" 2>&1
  rc=$?
  t1=$(date +%s.%N)
  local secs
  secs=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.2f", b - a }')
  if [ "$rc" = 0 ]; then
    say "$name ok in ${secs}s"
  else
    local why="failed"
    [ "$rc" = 124 ] || [ "$rc" = 137 ] && why="TIMED OUT after ${limit}s"
    say "$name $why (rc $rc, ${secs}s); last lines of logs/$name.log:"
    tail -n 20 "$log" | sed 's/^/    /' >&2
  fi
  record "$name" "$rc" "$secs" "logs/$name.log"
  return "$rc"
}

# --- The OpenCL ICD loader (libOpenCL.so.1) and the vendor's ICD ---------------------------
have_libopencl() {
  ldconfig -p 2>/dev/null | grep -q 'libOpenCL\.so\.1 ' && return 0
  local d
  for d in ${LD_LIBRARY_PATH//:/ }; do [ -e "$d/libOpenCL.so.1" ] && return 0; done
  return 1
}
# Unpacks .deb files into $WORK/debs (not into /) and puts their library folders first.
unpack_debs() {
  local deb
  for deb in "$@"; do
    [ -f "$deb" ] || { echo "not a file: $deb"; return 1; }
    if command -v dpkg-deb > /dev/null; then
      dpkg-deb -x "$deb" "$WORK/debs" || return 1
    else  # ar + tar: a .deb is an ar archive holding data.tar.*
      (mkdir -p "$WORK/debs/ar" && cd "$WORK/debs/ar" && ar x "$deb" &&
        tar -xf data.tar.* -C "$WORK/debs" && rm -f ./*) || return 1
    fi
    echo "unpacked $deb"
  done
  local d
  for d in "$WORK"/debs/usr/lib/x86_64-linux-gnu "$WORK"/debs/usr/lib "$WORK"/debs/lib/x86_64-linux-gnu; do
    [ -d "$d" ] && export LD_LIBRARY_PATH="$d${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  done
  return 0
}
icd_part() {
  local t0 rc=0 note="" log=$WORK/logs/icd.log
  mkdir -p "$WORK/logs"
  t0=$(date +%s)
  {
    if [ -n "${SGNLF_DEBS:-}" ]; then
      unpack_debs "$SGNLF_DEBS"/*.deb || rc=1
    fi
    if have_libopencl; then
      note="libOpenCL.so.1 present"
    elif [ -n "${SGNLF_ICD_DEB:-}" ]; then
      unpack_debs "$SGNLF_ICD_DEB" || rc=1
      note="libOpenCL.so.1 from $SGNLF_ICD_DEB"
    elif command -v apt-get > /dev/null && [ "$(id -u)" = 0 ] &&
      timeout 90 apt-get install -y --no-install-recommends ocl-icd-libopencl1; then
      note="libOpenCL.so.1 installed by apt-get"
    else
      rc=1
      note="libOpenCL.so.1 (the OpenCL ICD loader) is missing and could not be installed: give SGNLF_ICD_DEB=ocl-icd-libopencl1_*.deb (apt-get download ocl-icd-libopencl1 where the network is reachable)"
    fi
    have_libopencl || { rc=1; note="$note; libOpenCL.so.1 still not found"; }
    # The vendors' ICDs: ocl-icd reads /etc/OpenCL/vendors/*.icd (or OCL_ICD_VENDORS). A
    # container may hold NVIDIA's libnvidia-opencl.so.1 without its .icd file: then a private
    # vendors folder names it beside the registered ones.
    local vendors=${OCL_ICD_VENDORS:-/etc/OpenCL/vendors} nv=""
    ls "$vendors"/*.icd 2>/dev/null && cat "$vendors"/*.icd 2>/dev/null
    if ! grep -qs nvidia "$vendors"/*.icd 2>/dev/null; then
      nv=$(ldconfig -p 2>/dev/null | awk '/libnvidia-opencl\.so\.1 / { print $NF; exit }')
      local d
      for d in /usr/local/nvidia/lib64 /usr/local/nvidia/lib /usr/lib/x86_64-linux-gnu /usr/lib64; do
        [ -z "$nv" ] && [ -e "$d/libnvidia-opencl.so.1" ] && nv=$d/libnvidia-opencl.so.1
      done
      if [ -n "$nv" ]; then
        mkdir -p "$WORK/vendors"
        cp "$vendors"/*.icd "$WORK/vendors/" 2>/dev/null
        echo "$nv" > "$WORK/vendors/nvidia.icd"
        export OCL_ICD_VENDORS=$WORK/vendors
        note="$note; NVIDIA ICD $nv registered privately (OCL_ICD_VENDORS)"
      fi
    fi
    echo "$note"
  } > "$log" 2>&1
  # (the block above runs in this shell, so its exports stay)
  [ "$rc" = 0 ] && say "icd: $note" || { say "icd FAILED: $note"; tail -n 20 "$log" >&2; }
  record icd "$rc" "$(($(date +%s) - t0))" logs/icd.log "$note"
}

# --- The parts ---------------------------------------------------------------------------
want icd && icd_part

if want build; then
  if [ -n "${SGNLF_BUILD_DIR:-}" ]; then
    say "build skipped: SGNLF_BUILD_DIR=$BUILD"
    record build skipped 0 "" "prebuilt $BUILD"
  else
    part build "$T_BUILD" bash scripts/build.sh
  fi
fi
SGNLF=$BUILD/bin/sgnlf
# A prebuilt folder made in another checkout names that checkout's paths (the tests' fixtures,
# their temporary folders): where that path does not exist here, link it to this checkout.
if [ -f "$BUILD/CMakeCache.txt" ]; then
  src=$(sed -n 's/^CMAKE_HOME_DIRECTORY:INTERNAL=//p' "$BUILD/CMakeCache.txt")
  if [ -n "$src" ] && [ "$src" != "$ROOT" ] && [ ! -e "$src" ]; then
    if mkdir -p "$(dirname "$src")" 2>/dev/null && ln -s "$ROOT" "$src" 2>/dev/null; then
      say "linked $src -> $ROOT (the source path the prebuilt build names)"
    else
      say "warning: the build names the source path $src, which does not exist here (tests that read fixtures may fail)"
    fi
  fi
fi
# A prebuilt folder from another machine may lack libraries here: name them.
if [ -x "$SGNLF" ]; then
  missing=$(ldd "$SGNLF" "$BUILD"/bin/bench_* 2>/dev/null | awk '/not found/ { print $1 }' | sort -u | tr '\n' ' ')
  [ -n "$missing" ] && { say "libraries not found for the binaries: $missing(give their .deb files in SGNLF_DEBS)"; record libraries 1 0 "" "not found: $missing"; }
else
  say "$SGNLF missing: no build"
  record libraries 1 0 "" "$SGNLF missing"
fi

if want devices; then
  part devices "$T_DEVICES" "$SGNLF" devices --smoke
  part devices_json "$T_DEVICES" bash -c "\"$SGNLF\" devices --json > \"$WORK/devices.json\""
fi

if want tests; then
  found=0
  for f in "$BUILD"/tests/oclgrind/device_cases/*.cases; do
    [ -e "$f" ] || continue
    found=1
    family=$(basename "$f" .cases)
    bin=$(sed -n 1p "$f")
    spec=$(sed -n 2p "$f")
    # A case name that matches nothing is a case not run: Catch2 says so and passes.
    if part "test_$family" "$T_TEST" "$BUILD/$bin" "$spec" &&
      grep -q '^No test cases matched' "$WORK/logs/test_$family.log"; then
      say "test_$family: $(grep '^No test cases matched' "$WORK/logs/test_$family.log" | tr '\n' ' ')"
      record "test_${family}_cases" 1 0 "logs/test_$family.log" "a case name matched no test case"
    fi
  done
  [ "$found" = 1 ] || { say "tests: no case lists in $BUILD/tests/oclgrind/device_cases (configure a build that has them)"; record tests 1 0 "" "no case lists"; }
  # The MLP GEMMs in full under the gpu profile's local tiles: Oclgrind's list keeps only their
  # small case (the simulator is slow), a GPU runs every one.
  [ -x "$BUILD/tests/field/test_field" ] &&
    part test_field_mlp "$T_TEST" env SGNLF_DEVICE_PROFILE=gpu "$BUILD/tests/field/test_field" --warn NoTests "[mlp],[mlp_tiles]"
fi

if want bench; then
  mkdir -p "$WORK/bench"
  for entry in $BENCH; do
    b=${entry%%:*}
    filter=${entry#*:}
    part "bench_${b#bench_}" "$T_BENCH" "$BUILD/bin/$b" "--benchmark_filter=$filter" \
      "--benchmark_min_time=$MIN_TIME" --benchmark_repetitions=3 \
      --benchmark_report_aggregates_only=true "--benchmark_out=$WORK/bench/$b.json" \
      --benchmark_out_format=json
  done
fi

if want train; then
  mkdir -p "$WORK/train"
  # shellcheck disable=SC2086  # SIM_ARGS are words
  if part simulate "$T_SIM" "$SGNLF" simulate --sequence kitti360-1538 --out "$WORK/data" $SIM_ARGS; then
    for m in $METHODS; do
      # The first STEPS steps of the preset's schedule (--stop-at: no evaluation, no final
      # stages); summary.json carries train_seconds, steps_per_s and, for the pose-free
      # methods, the geometric stage's seconds (host work before the first epoch).
      part "train_$m" "$T_TRAIN" "$SGNLF" train --method "$m" --preset "$PRESET" \
        --data "$WORK/data" --out "$WORK/train/$m" --no-resume --stop-at "$STEPS"
      for f in summary.json train_log.jsonl; do
        [ -f "$WORK/train/$m/$f" ] && cp "$WORK/train/$m/$f" "$WORK/train/$m.$f"
      done
    done
  fi
fi

# --- The report ----------------------------------------------------------------------------
TOTAL=$(($(date +%s) - T_START))
export GPU_CHECK_WORK=$WORK GPU_CHECK_TOTAL=$TOTAL GPU_CHECK_STEPS=$STEPS GPU_CHECK_PRESET=$PRESET \
  GPU_CHECK_BUILD=$BUILD GPU_CHECK_METHODS=$METHODS
if command -v python3 > /dev/null; then
  python3 scripts/gpu_check_report.py > "$OUT_DIR/gpu-check.json" || { say "report FAILED"; FAILED=1; }
else
  # Without python3: the parts alone, no medians (they stay in the logs' benchmark JSONs).
  {
    echo '{"note": "python3 missing: benchmark medians and training rates not extracted (gpu-check-logs.tar.gz)",'
    echo " \"total_seconds\": $TOTAL, \"parts\": ["
    awk -F'\t' '{ gsub(/"/, "\\\"", $5); printf "%s  {\"name\": \"%s\", \"rc\": \"%s\", \"seconds\": %s, \"note\": \"%s\"}", (NR > 1 ? ",\n" : ""), $1, $2, $3, $5 }' "$PARTS_TSV"
    echo ']}'
  } > "$OUT_DIR/gpu-check.json"
  say "python3 missing: gpu-check.json holds the parts only"
fi
tar -czf "$OUT_DIR/gpu-check-logs.tar.gz" -C "$WORK" logs $(cd "$WORK" && ls -d bench train/*.summary.json train/*.train_log.jsonl devices.json 2>/dev/null) \
  || say "could not write gpu-check-logs.tar.gz"
say "wrote $OUT_DIR/gpu-check.json and gpu-check-logs.tar.gz in ${TOTAL}s; $(awk -F'\t' '$2 != 0 && $2 != "skipped" { n++ } END { print n + 0 }' "$PARTS_TSV") part(s) failed"
rm -rf "$WORK"
exit "$FAILED"
