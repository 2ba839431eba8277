#!/usr/bin/env bash
# CTest script: runs the README's scale-out lines (the fenced block between the markers
# "<!-- scale-out:" and "<!-- /scale-out -->" in README.md) on a smoke table and checks the
# merged table against the one-process run of the same table.
#   scale_out.sh slurm|parallel --sgnlf BIN --readme README.md --table T --scale S --seeds 1
#                --one ONE/results.json --baseline COMMITTED/results.json --out DIR
# The block's first line sets T, S, SEEDS and SGNLF; the test replaces it with its own and runs
# the rest verbatim with bash in DIR/work: the lines before the first comment, then the section
# of the mode (the comment naming "Slurm", or "GNU parallel"), then the one after "# then" (the
# merge). Mode slurm first starts a one-node Slurm on localhost, all in a temporary folder:
# munged (its own key and socket), slurmctld and slurmd (slurm.conf: this host, nproc CPUs,
# proctrack/linuxproc, task/none, no cgroups, free ports), waits for the node to be idle, and
# stops them on exit whatever happens (their logs are kept in DIR/slurm-logs).
# Checks: `sgnlf compare --equal` of the merged table with ONE (every field but times, paths and
# context: results/schema.md "Cells") and `sgnlf compare --strict` with the committed BASELINE
# must pass; and, to show they bite, a merge without the last cell must be refused (exit 2)
# naming it, and a merge whose last cell has a changed metric must fail both comparisons (exit 4).
# Exit 77 (CTest skip) when the mode's programs are not installed (scripts/setup.sh with
# SGNLF_SETUP_SCALE_OUT=1), unless CI=true or SGNLF_REQUIRE_SCALE_OUT=1, where that fails.
set -uo pipefail
mode=${1:-}
[ $# -gt 0 ] && shift
sgnlf="" readme="" table="" scale="" seeds="" one="" baseline="" out=""
while [ $# -gt 1 ]; do
  case $1 in
    --sgnlf) sgnlf=$2 ;; --readme) readme=$2 ;; --table) table=$2 ;; --scale) scale=$2 ;;
    --seeds) seeds=$2 ;; --one) one=$2 ;; --baseline) baseline=$2 ;; --out) out=$2 ;;
    *) break ;;
  esac
  shift 2
done
if [ $# -ne 0 ] || { [ "$mode" != slurm ] && [ "$mode" != parallel ]; } || [ -z "$sgnlf" ] ||
   [ -z "$readme" ] || [ -z "$table" ] || [ -z "$scale" ] || [ -z "$seeds" ] || [ -z "$one" ] ||
   [ -z "$baseline" ] || [ -z "$out" ]; then
  echo "usage: $0 slurm|parallel --sgnlf BIN --readme README.md --table T --scale S --seeds N" \
       "--one RESULTS --baseline RESULTS --out DIR" >&2
  exit 2
fi
die() { echo "scale_out.sh ($mode): $*" >&2; exit 1; }

# The mode's programs.
case $mode in
  slurm) needed=(munged munge unmunge slurmctld slurmd sbatch sinfo squeue scancel) ;;
  parallel) needed=(parallel) ;;
esac
missing=()
for p in "${needed[@]}"; do command -v "$p" >/dev/null 2>&1 || missing+=("$p"); done
if [ ${#missing[@]} -gt 0 ]; then
  msg="not installed: ${missing[*]} (Debian slurm-wlm, munge, parallel: SGNLF_SETUP_SCALE_OUT=1 bash scripts/setup.sh)"
  if [ "${CI:-}" = "true" ] || [ "${SGNLF_REQUIRE_SCALE_OUT:-0}" = "1" ]; then die "$msg"; fi
  echo "scale_out.sh ($mode): $msg: skipped" >&2
  exit 77
fi
[ -f "$one" ] || die "the one-process result $one is missing (run the harness_smoke_table_low test)"
[ -f "$baseline" ] || die "the committed baseline $baseline is missing"
sgnlf=$(cd "$(dirname "$sgnlf")" && pwd)/$(basename "$sgnlf")
[ -x "$sgnlf" ] || die "$sgnlf is not an executable"

# The README's block, cut into its parts.
block=$(awk '/^<!-- \/scale-out -->/ { inside = 0 } inside { print } /^<!-- scale-out:/ { inside = 1 }' "$readme")
mapfile -t lines <<< "$block"
n=${#lines[@]}
if [ "$n" -lt 4 ] || [ "${lines[0]}" != '```bash' ] || [ "${lines[n-1]}" != '```' ]; then
  die "$readme has no fenced bash block between '<!-- scale-out: ...' and '<!-- /scale-out -->'"
fi
params_re='^T=[^ ]+ S=[^ ]+ SEEDS=[^ ]+ SGNLF=[^ ]+$'
[[ "${lines[1]}" =~ $params_re ]] ||
  die "the scale-out block of $readme must start with 'T=... S=... SEEDS=... SGNLF=...', not '${lines[1]}'"
common="" slurm="" parallel="" merge="" part=common
for ((i = 2; i < n - 1; i++)); do
  l=${lines[i]}
  if [[ "$l" == "#"* ]]; then
    case $l in
      *Slurm*) part=slurm ;;
      *"GNU parallel"*) part=parallel ;;
      "# then"*) part=merge ;;
      *) die "the scale-out block of $readme has a comment naming no part (Slurm, GNU parallel, then): '$l'" ;;
    esac
    continue
  fi
  printf -v "$part" '%s%s\n' "${!part}" "$l"
done
for p in common slurm parallel merge; do
  [ -n "${!p//[[:space:]]/}" ] || die "the scale-out block of $readme has no '$p' lines"
done
# Only the parameters are the test's own; the commands run as the README has them.
script="set -euo pipefail
$(printf 'T=%q S=%q SEEDS=%q SGNLF=%q' "$table" "$scale" "$seeds" "$sgnlf")
$common${!mode}$merge"

rm -rf "$out"
mkdir -p "$out/work" || die "cannot create $out/work"
printf '%s' "$script" > "$out/readme-lines.sh"
# The lines run in the background (so that a TERM to this script runs its traps at once: bash
# holds them while a foreground command runs), under `timeout`, which leads its own process
# group: killed whole on exit.
lines_pid=""
kill_lines() { [ -z "$lines_pid" ] || kill -TERM -- "-$lines_pid" 2>/dev/null; }
trap kill_lines EXIT
trap 'exit 143' TERM INT

if [ "$mode" = slurm ]; then
  sd=$(mktemp -d "${TMPDIR:-/tmp}/sgnlf-slurm.XXXXXX") || die "mktemp failed"
  pids=()
  # Each daemon runs under `timeout`, the leader of its own process group: TERM reaches the
  # daemon through it, KILL reaches both through the group.
  stop() {  # PID: TERM, up to 10 s, then KILL
    local k
    kill "$1" 2>/dev/null || return 0
    for ((k = 0; k < 50; k++)); do kill -0 "$1" 2>/dev/null || break; sleep 0.2; done
    kill -0 "$1" 2>/dev/null && { echo "$2 did not stop within 10 s: killed" >&2; kill -KILL -- "-$1" 2>/dev/null; }
    wait "$1" 2>/dev/null
  }
  cleanup() {
    kill_lines
    # pids: munged, slurmctld, slurmd. Jobs left are cancelled and their end reported while
    # slurmctld and munged still run; then slurmd, slurmctld and munged stop in that order.
    if [ ${#pids[@]} -ge 2 ] && kill -0 "${pids[1]}" 2>/dev/null; then
      local jobs_left k
      jobs_left=$(squeue -h -o %A 2>/dev/null)
      if [ -n "$jobs_left" ]; then
        scancel $jobs_left 2>/dev/null
        for ((k = 0; k < 50; k++)); do [ -z "$(squeue -h -o %A 2>/dev/null)" ] && break; sleep 0.2; done
      fi
    fi
    [ ${#pids[@]} -lt 3 ] || stop "${pids[2]}" slurmd
    [ ${#pids[@]} -lt 2 ] || stop "${pids[1]}" slurmctld
    [ ${#pids[@]} -lt 1 ] || stop "${pids[0]}" munged
    mkdir -p "$out/slurm-logs"
    cp "$sd"/slurm.conf "$sd"/log/* "$out/slurm-logs/" 2>/dev/null
    rm -rf "$sd"
  }
  trap cleanup EXIT
  show_logs() {
    local f
    for f in "$sd"/log/*; do [ -s "$f" ] && { echo "--- $f (last 30 lines)"; tail -n 30 "$f"; }; done >&2
  }
  # munged checks that its socket's folder is reachable by all and its key private.
  chmod 755 "$sd"
  mkdir -p "$sd/munge" "$sd/socket" "$sd/state" "$sd/spool" "$sd/log"
  chmod 700 "$sd/munge"
  chmod 755 "$sd/socket"
  head -c 1024 /dev/urandom > "$sd/munge/munge.key" && chmod 400 "$sd/munge/munge.key" ||
    die "cannot write the munge key"
  sock=$sd/socket/munge.socket
  # Each daemon under `timeout`: should this script be killed before its trap runs, they still
  # end within the test's time limit.
  life=${SGNLF_SCALE_OUT_DAEMON_S:-590}
  timeout "$life" munged -F --key-file="$sd/munge/munge.key" --socket="$sock" \
    --pid-file="$sd/munged.pid" --log-file="$sd/log/munged.log" --seed-file="$sd/munge/seed" \
    > "$sd/log/munged.out" 2>&1 &
  pids+=($!)
  for ((i = 0; i < 50; i++)); do
    munge -S "$sock" -n 2>/dev/null | unmunge -S "$sock" >/dev/null 2>&1 && break
    sleep 0.2
  done
  [ "$i" -lt 50 ] || { show_logs; die "munged did not start (a credential could not be made and decoded on $sock)"; }

  free_port() {  # a TCP port nothing listens on
    local p
    for ((k = 0; k < 100; k++)); do
      p=$((20000 + RANDOM % 40000))
      (exec 3<>"/dev/tcp/127.0.0.1/$p") 2>/dev/null || { echo "$p"; return; }
    done
    return 1
  }
  ctld_port=$(free_port) && slurmd_port=$(free_port) || die "no free TCP port found"
  [ "$ctld_port" != "$slurmd_port" ] || slurmd_port=$((ctld_port + 1))
  host=$(hostname -s)
  cat > "$sd/slurm.conf" <<EOF
ClusterName=sgnlftest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=$(id -un)
SlurmdUser=$(id -un)
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$sock
StateSaveLocation=$sd/state
SlurmdSpoolDir=$sd/spool
SlurmctldPidFile=$sd/slurmctld.pid
SlurmdPidFile=$sd/slurmd.pid
SlurmctldLogFile=$sd/log/slurmctld.log
SlurmdLogFile=$sd/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
MailProg=/bin/true
ReturnToService=2
SlurmctldDebug=info
SlurmdDebug=info
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=sgnlf Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
  export SLURM_CONF=$sd/slurm.conf
  timeout "$life" slurmctld -D -i -f "$SLURM_CONF" > "$sd/log/slurmctld.out" 2>&1 &
  pids+=($!)
  timeout "$life" slurmd -D -N "$host" -f "$SLURM_CONF" > "$sd/log/slurmd.out" 2>&1 &
  pids+=($!)
  state=""
  for ((i = 0; i < 120; i++)); do
    state=$(sinfo -h -N -n "$host" -o %t 2>/dev/null)
    [ "$state" = idle ] && break
    for p in "${pids[@]}"; do
      kill -0 "$p" 2>/dev/null || { show_logs; die "a Slurm daemon exited (logs above)"; }
    done
    sleep 0.5
  done
  [ "$state" = idle ] || { show_logs; die "node $host is not idle after 60 s (sinfo: '${state:-no answer}')"; }
  echo "slurm: node $host idle ($(nproc) CPUs; slurmctld port $ctld_port, slurmd port $slurmd_port; $sd)"
fi

echo "--- the README's lines, as run in $out/work:"
cat "$out/readme-lines.sh"
echo "---"
t0=$(date +%s)
(cd "$out/work" && exec timeout 480 bash "$out/readme-lines.sh") &
lines_pid=$!
wait "$lines_pid"
rc=$?
lines_pid=""
if [ "$mode" = slurm ]; then
  if [ "$rc" -ne 0 ]; then
    for f in "$out"/work/slurm-*.out; do [ -f "$f" ] && { echo "--- $f"; tail -n 20 "$f"; }; done
  fi
  echo "slurm jobs: $(ls "$out"/work/slurm-*.out 2>/dev/null | sed 's|.*/slurm-||; s|\.out$||' | tr '\n' ' ')"
fi
[ "$rc" -eq 0 ] || { [ "$mode" = slurm ] && show_logs; die "the README's lines failed (exit $rc)"; }
echo "the README's lines ran in $(( $(date +%s) - t0 )) s"

merged=$out/work/runs/$table/results.json
[ -f "$merged" ] || die "the README's merge line wrote no $merged"
"$sgnlf" compare --equal "$merged" "$one" || die "the merged cells differ from the one-process run $one"
"$sgnlf" compare --strict "$merged" "$baseline" >"$out/compare.txt" ||
  { cat "$out/compare.txt"; die "the merged table does not match the committed $baseline"; }

# The checks bite: a missing cell is refused, naming it; a changed metric fails both comparisons.
mapfile -t cells < <(ls -d "$out"/work/cells/* | sort -V)
last=$(( ${#cells[@]} - 1 ))
[ "$last" -ge 1 ] || die "the README's lines left ${#cells[@]} cell(s) under $out/work/cells"
[ "${cells[last]##*/}" = "$last" ] || die "cell folders are not 0..$last: ${cells[*]##*/}"
"$sgnlf" merge --out "$out/partial" "${cells[@]:0:last}" >/dev/null 2>"$out/partial.err"
rc=$?
[ "$rc" -eq 2 ] && grep -q "1 of $((last + 1)) cells missing: $last " "$out/partial.err" ||
  { cat "$out/partial.err"; die "a merge without cell $last was not refused naming it (exit $rc)"; }
# The last cell (SG-NLF's): its CD is a number (LiDAR4D's smoke cells predict no returns).
mkdir -p "$out/tampered"
cat > "$out/tamper.cmake" <<'EOF'
file(READ ${IN} cell)
string(JSON cd GET "${cell}" outcome entry metrics cd)
if(NOT cd MATCHES "^[0-9.eE+-]+$")
  message(FATAL_ERROR "${IN}: outcome.entry.metrics.cd is '${cd}', not a number")
endif()
string(JSON cell SET "${cell}" outcome entry metrics cd "1000.0")
file(WRITE ${OUT} "${cell}")
EOF
cmake -DIN="${cells[last]}/cell.json" -DOUT="$out/tampered/cell.json" -P "$out/tamper.cmake" ||
  die "cannot write a changed copy of ${cells[last]}/cell.json"
"$sgnlf" merge --out "$out/merged-tampered" "${cells[@]:0:last}" "$out/tampered" >/dev/null ||
  die "the merge with a changed cell failed"
"$sgnlf" compare --equal "$out/merged-tampered/results.json" "$one" >"$out/tampered-equal.txt"
rc=$?
[ "$rc" -eq 4 ] || { cat "$out/tampered-equal.txt"; die "compare --equal did not tell a changed cell from the one-process run (exit $rc)"; }
"$sgnlf" compare --strict "$out/merged-tampered/results.json" "$baseline" >"$out/tampered-strict.txt"
rc=$?
[ "$rc" -eq 4 ] || { cat "$out/tampered-strict.txt"; die "compare --strict did not flag the changed cell (exit $rc)"; }
echo "scale_out.sh ($mode): the README's lines made ${#cells[@]} cells; merged, they equal the" \
     "one-process run; a missing and a changed cell are caught"
