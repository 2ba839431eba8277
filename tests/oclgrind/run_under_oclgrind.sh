#!/usr/bin/env bash
# Runs one test binary under Oclgrind (Debian's `oclgrind`, an OpenCL device simulator) and
# fails on any report it makes: out-of-bounds accesses, data races, uninitialised values,
# barrier divergence, API errors (whatever the options given enable).
#   run_under_oclgrind.sh [oclgrind options ...] -- BINARY [arguments ...]
# `oclgrind` preloads its own OpenCL runtime, so the binary sees one platform, "Oclgrind";
# SGNLF_DEVICE=Oclgrind makes the project's device choice (runtime/cl/device.hpp) say so, and
# fail rather than run on another device. Oclgrind writes its kernel reports to --log, which
# stays empty on a clean run, and those of --check-api to stderr, which is searched for them. Exit 77 (CTest skip) when oclgrind is not installed, unless CI=true or
# SGNLF_REQUIRE_OCLGRIND=1, where that fails.
set -uo pipefail
opts=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do opts+=("$1"); shift; done
if [ "${1:-}" != "--" ] || [ $# -lt 2 ]; then
  echo "usage: $0 [oclgrind options ...] -- BINARY [arguments ...]" >&2
  exit 2
fi
shift
# Each comma-separated pattern of the Catch2 test spec (the argument after the binary) must match
# a test case: Catch2 runs nothing for a pattern that matches nothing and passes, so a renamed
# case (or a name split at a ';' by CMake) would leave its kernels unchecked without a word.
# Listed natively (no OpenCL device is created), before the check for oclgrind itself.
if [ $# -ge 2 ] && [ "${2#-}" = "$2" ]; then
  IFS=',' read -r -a patterns <<< "$2"
  unmatched=0
  for p in "${patterns[@]}"; do
    names=$("$1" "$p" --list-test-names-only 2>/dev/null)  # rc = the count listed
    if [ -z "$(printf '%s' "$names" | tr -d '[:space:]')" ]; then
      echo "the case pattern '$p' matches no test case of $1 (tests/oclgrind/CMakeLists.txt)" >&2
      unmatched=$((unmatched + 1))
    fi
  done
  [ "$unmatched" -eq 0 ] || exit 1
fi
if ! command -v oclgrind >/dev/null 2>&1; then
  if [ "${CI:-}" = "true" ] || [ "${SGNLF_REQUIRE_OCLGRIND:-0}" = "1" ]; then
    echo "oclgrind is not installed (apt-get install oclgrind, or scripts/setup.sh)" >&2
    exit 1
  fi
  echo "oclgrind is not installed: skipped (apt-get install oclgrind, or scripts/setup.sh)" >&2
  exit 77
fi
log=$(mktemp "${TMPDIR:-/tmp}/sgnlf-oclgrind.XXXXXX")
out=$(mktemp "${TMPDIR:-/tmp}/sgnlf-oclgrind-out.XXXXXX")
trap 'rm -f "$log" "$out"' EXIT
SGNLF_DEVICE=Oclgrind oclgrind --log "$log" "${opts[@]}" "$@" > "$out" 2>&1
rc=$?
cat "$out"
# --check-api prints its reports to stderr, not to the log.
api=$(grep -c '^Oclgrind - OpenCL runtime error detected' "$out")
if [ "$api" -gt 0 ]; then
  echo "oclgrind reported $api OpenCL API error(s) (above, 'Oclgrind - OpenCL runtime error detected')" >&2
  exit 1
fi
if [ -s "$log" ]; then
  # Each report starts with an unindented line naming its kind, then an indented "Kernel:"
  # line; count them by kind and kernel (addresses dropped).
  echo "oclgrind reported (count, kind, kernel; the log's first 200 lines follow):" >&2
  awk '/^[^[:space:]]/ { kind = $0; gsub(/0x[0-9a-f]+/, "ADDR", kind); if (!(kind in seen)) seen[kind] = 0 }
       /^[[:space:]]+Kernel:/ { sub(/^[[:space:]]+Kernel:[[:space:]]*/, ""); n[kind " | " $0]++; seen[kind] = 1 }
       END { for (k in n) printf "%7d  %s\n", n[k], k; for (k in seen) if (!seen[k]) printf "%7s  %s\n", "?", k }' \
    "$log" | sort -rn >&2
  head -n 200 "$log" >&2
  exit 1
fi
if [ "$rc" -eq 77 ]; then
  echo "the binary found no OpenCL platform under oclgrind" >&2
  exit 1
fi
exit "$rc"
