#!/usr/bin/env bash
# Where a clean clone's CI time goes (issue 57, item 7). Clones this checkout's
# HEAD into a fresh folder and runs there what .ci/run runs -- scripts/setup.sh
# (apt-get, configure, build, the main job) and the README's test command --
# without a compiler cache, then prints each phase's wall time and CPU time
# (user + system of everything it ran). On a shared machine the wall times
# grow with the other jobs' load; the CPU times do not, nearly: compare those.
#
#   bash scripts/ci_timing.sh [--apt] [--keep] [--costs]
#     --apt    run apt-get as setup.sh does (needs root or sudo); default SKIP_APT=1
#     --keep   keep the clone (default: removed at the end)
#     --costs  also print every test of 1.5 s or more in tests/test_costs.tsv's format
# Environment: CI_TIMING_DIR (the clone; default a new folder under /tmp), JOBS
# (setup.sh's build jobs, default nproc), TU_TIME_LOG (a file: every compile
# and link's CPU time, through scripts/tu_time.sh as the compiler launcher).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
SRC=$PWD

APT=0 KEEP=0 COSTS=0
for a in "$@"; do
  case $a in
    --apt) APT=1 ;;
    --keep) KEEP=1 ;;
    --costs) COSTS=1 ;;
    -h|--help) sed -n '2,17p' "$0"; exit 0 ;;
    *) echo "ci_timing.sh: unknown argument '$a' (see --help)" >&2; exit 2 ;;
  esac
done

DIR=${CI_TIMING_DIR:-$(mktemp -d /tmp/drape-ci-timing.XXXXXX)}
[[ $KEEP == 1 ]] || trap 'rm -rf "$DIR"' EXIT
LOG=$DIR.log
echo "ci_timing: $(date -u '+%F %T') UTC, $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg), commit $(git rev-parse --short HEAD)"
echo "ci_timing: cloning into $DIR (log: $LOG)"
rm -rf "$DIR"
git clone -q --no-hardlinks "$SRC" "$DIR"

export CCACHE_DISABLE=1  # a clean machine has no compiler cache (setup.sh uses none anyway)
launcher=()
if [[ -n ${TU_TIME_LOG:-} ]]; then
  export TU_TIME_ROOT=$DIR
  launcher=(env CMAKE_CXX_COMPILER_LAUNCHER="$SRC/scripts/tu_time.sh" CMAKE_C_COMPILER_LAUNCHER="$SRC/scripts/tu_time.sh")
fi
cd "$DIR"
skip_apt=1
[[ $APT == 1 ]] && skip_apt=0
start=$(date +%s.%N)
"${launcher[@]}" env SKIP_APT=$skip_apt BUILD_DIR=build bash scripts/setup.sh </dev/null >"$LOG" 2>&1 ||
  { tail -n 30 "$LOG"; echo "ci_timing: setup.sh failed (log: $LOG)" >&2; exit 1; }
setup_end=$(date +%s.%N)
tests_time=$( { /usr/bin/time -f '%e %U %S' ctest --test-dir build --output-on-failure --no-tests=error -j2 --timeout 900 \
  >>"$LOG" 2>&1; } 2>&1 | tail -n 1) || true
tests_ok=$(grep -Eo '[0-9]+% tests passed, [0-9]+ tests failed out of [0-9]+' "$LOG" | tail -n 1)
end=$(date +%s.%N)

# setup.sh's steps: "==> [HH:MM:SS, <cpu> s CPU] <what>", CPU cumulative.
awk -v end_wall="$setup_end" -v start_wall="$start" '
  /^==> \[[0-9:]+, [0-9.]+ s CPU\]/ {
    split(substr($2, 2), hms, /[:,]/); t = hms[1] * 3600 + hms[2] * 60 + hms[3]
    cpu = $3; what = $0; sub(/^==> \[[^]]*\] /, "", what)
    phase = what ~ /^(Installing|Skipping apt)/ ? "apt-get" : what ~ /^Configuring/ ? "configure" :
            what ~ /^Building/ ? "build" : what ~ /^Done/ ? "done" : "main job"
    if (n == 0 || phase != name[n]) { n++; name[n] = phase; t0[n] = t; c0[n] = cpu }
    last_t = t; last_c = cpu
  }
  END {
    for (i = 1; i < n; i++) { wall[name[i]] += t0[i + 1] - t0[i]; cpu[name[i]] += c0[i + 1] - c0[i] }
    split("apt-get configure build main job", order, " ")
    order[4] = "main job"; delete order[5]
    for (i = 1; i <= 4; i++) printf "%-10s %7.0f s wall %7.0f s CPU\n", order[i], wall[order[i]], cpu[order[i]]
  }' "$LOG"
read -r tw tu ts <<<"$tests_time"
printf '%-10s %7.0f s wall %7.0f s CPU   (%s)\n' tests "$tw" "$(echo "$tu + $ts" | bc)" "$tests_ok"
printf '%-10s %7.0f s wall               (clone to passing tests; load now %s)\n' total "$(echo "$end - $start" | bc)" \
  "$(cut -d' ' -f1-3 /proc/loadavg)"

# The slowest tests (ctest's own log of this run).
echo "slowest tests (s, under ctest -j2):"
awk '/^[0-9]+\/[0-9]+ Test: /{ sub(/^[0-9]+\/[0-9]+ Test: /, ""); name = $0 }
     /^"?Test time = /{ printf "%8.1f  %s\n", $(NF - 1), name }' build/Testing/Temporary/LastTest.log | sort -rn | head -n 15
if [[ $COSTS == 1 ]]; then
  echo "tests of 1.5 s or more (tests/test_costs.tsv):"
  awk '/^[0-9]+\/[0-9]+ Test: /{ sub(/^[0-9]+\/[0-9]+ Test: /, ""); name = $0 }
       /^"?Test time = /{ t = $(NF - 1); if (t >= 1.5) printf "%.0f\t%s\n", t + 0.5, name }' \
    build/Testing/Temporary/LastTest.log | sort -t$'\t' -k1,1rn
fi
[[ $tests_ok == *" 0 tests failed"* ]]
