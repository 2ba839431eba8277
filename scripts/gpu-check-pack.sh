#!/usr/bin/env bash
# Packs what scripts/gpu-check.sh needs from this machine's build into DIR (default
# .gpu-check, which .git/info/exclude should ignore), for a GPU machine that cannot build the
# project or fetch packages: DIR/build holds sgnlf, the benchmark binaries, the test binaries
# of the device case lists and those lists, and CMakeCache.txt (the source path the binaries
# name); DIR/debs the .deb files of their runtime libraries (apt-get download). A few tens of
# MiB. Then, there:
#   SGNLF_BUILD_DIR=DIR/build SGNLF_ICD_DEB=$(ls DIR/debs/ocl-icd-libopencl1_*.deb) \
#     SGNLF_DEBS=DIR/debs bash scripts/gpu-check.sh "$OUT"
# Build first (scripts/build.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
DIR=${1:-.gpu-check}
BUILD=${SGNLF_BUILD_DIR:-build}
[ -x "$BUILD/bin/sgnlf" ] || { echo "gpu-check-pack: $BUILD/bin/sgnlf missing (run scripts/build.sh)" >&2; exit 1; }
ls "$BUILD"/tests/oclgrind/device_cases/*.cases > /dev/null 2>&1 ||
  { echo "gpu-check-pack: no case lists in $BUILD/tests/oclgrind/device_cases" >&2; exit 1; }
rm -rf "$DIR/build"
mkdir -p "$DIR/build/bin" "$DIR/build/tests/oclgrind/device_cases" "$DIR/debs"
cp "$BUILD/CMakeCache.txt" "$DIR/build/"
cp "$BUILD/bin/sgnlf" "$BUILD"/bin/bench_* "$DIR/build/bin/"
for f in "$BUILD"/tests/oclgrind/device_cases/*.cases; do
  cp "$f" "$DIR/build/tests/oclgrind/device_cases/"
  bin=$(sed -n 1p "$f")
  mkdir -p "$DIR/build/$(dirname "$bin")"
  cp "$BUILD/$bin" "$DIR/build/$bin"
done
# The binaries' libraries outside glibc, as Debian packages (their files' owners).
pkgs=$(ldd "$DIR"/build/bin/* "$DIR"/build/tests/*/test_* 2>/dev/null |
  awk '$3 ~ /^\// { print $3 }' | sort -u | grep -v -e '/libc\.so' -e '/libm\.so' -e 'ld-linux' |
  xargs -r dpkg -S 2>/dev/null | cut -d: -f1 | sort -u)
(cd "$DIR/debs" && apt-get download $pkgs)
du -sh "$DIR" >&2
echo "gpu-check-pack: packed $DIR (packages: $(echo $pkgs))" >&2
