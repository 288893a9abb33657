#!/usr/bin/env bash
# Where a clean clone's CI time goes (issue 57, item 7). Clones this checkout's
# HEAD into a fresh folder and runs there what .ci/run runs -- scripts/setup.sh
# (apt-get, configure, build, the main job) and the README's test command --
# without a compiler cache (--warm: with this machine's ccache as it is), then prints each phase's wall time and CPU time
# (user + system of everything it ran). On a shared machine the wall times
# grow with the other jobs' load; the CPU times do not, nearly: compare those.
#
#   bash scripts/ci_timing.sh [--apt] [--keep] [--costs] [--warm]
#     --apt    run apt-get as setup.sh does (needs root or sudo); default SKIP_APT=1
#     --keep   keep the clone (default: removed at the end)
#     --costs  also print every test of 1.5 s or more in tests/test_costs.tsv's format
#     --warm   compile through ccache with its cache as it is (CI's second run on a machine);
#              run it twice on one commit for the warm figure (the first fills the cache)
# Environment: CI_TIMING_DIR (the clone; default a new folder beside this one), JOBS
# (setup.sh's build jobs, default nproc), TU_TIME_LOG (a file: every compile
# and link's CPU time, through scripts/tu_time.sh as the compiler launcher).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
SRC=$PWD

APT=0 KEEP=0 COSTS=0 WARM=0
for a in "$@"; do
  case $a in
    --apt) APT=1 ;;
    --keep) KEEP=1 ;;
    --costs) COSTS=1 ;;
    --warm) WARM=1 ;;
    -h|--help) sed -n '2,19p' "$0"; exit 0 ;;
    *) echo "ci_timing.sh: unknown argument '$a' (see --help)" >&2; exit 2 ;;
  esac
done

# Beside this checkout, so that ../shared/assets (the MakeHuman data a test uses) is found as from here.
DIR=${CI_TIMING_DIR:-$(mktemp -d "$(dirname "$SRC")/drape-ci-timing.XXXXXX")}
[[ $KEEP == 1 ]] || trap 'rm -rf "$DIR" "$DIR.time"' EXIT
LOG=$DIR.log
echo "ci_timing: $(date -u '+%F %T') UTC, $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg), commit $(git rev-parse --short HEAD)"
echo "ci_timing: cloning into $DIR (log: $LOG)"
rm -rf "$DIR"
git clone -q --no-hardlinks "$SRC" "$DIR"

[[ $WARM == 1 ]] || export CCACHE_DISABLE=1  # a fresh machine's compiler cache is empty: compile everything
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
/usr/bin/time -o "$DIR.time" -f '%e %U %S' ctest --test-dir build --output-on-failure --no-tests=error -j2 --timeout 900 \
  >>"$LOG" 2>&1 || true
tests_time=$(tail -n 1 "$DIR.time")
tests_ok=$(grep -Eo '[0-9]+% tests passed, [0-9]+ tests failed out of [0-9]+' "$LOG" | tail -n 1)
end=$(date +%s.%N)

# setup.sh's steps: "==> [HH:MM:SS, <cpu> s CPU] <what>", the CPU time cumulative.
/usr/bin/python3 - "$LOG" <<'PY'
import re, sys
steps = []
for line in open(sys.argv[1], errors="replace"):
    m = re.match(r"==> \[(\d+):(\d+):(\d+), ([\d.]+) s CPU\] (.*)", line)
    if m:
        h, mi, se, cpu, what = m.groups()
        phase = ("apt-get" if re.match(r"Installing|Skipping apt", what) else "configure" if what.startswith("Configuring")
                 else "build" if what.startswith("Building") else "done" if what.startswith("Done") else "main job")
        steps.append((phase, int(h) * 3600 + int(mi) * 60 + int(se), float(cpu)))
wall, cpu = {}, {}
for (phase, t, c), (_, t1, c1) in zip(steps, steps[1:]):
    wall[phase] = wall.get(phase, 0) + (t1 - t) % 86400
    cpu[phase] = cpu.get(phase, 0) + c1 - c
for phase in ("apt-get", "configure", "build", "main job"):
    print("%-10s %7.0f s wall %7.0f s CPU" % (phase, wall.get(phase, 0), cpu.get(phase, 0)))
PY
read -r tw tu ts <<<"$tests_time"
printf '%-10s %7.0f s wall %7.0f s CPU   (%s)\n' tests "$tw" "$(awk -v u="$tu" -v s="$ts" 'BEGIN { print u + s }')" "$tests_ok"
printf '%-10s %7.0f s wall               (clone to passing tests; load now %s)\n' total \
  "$(awk -v a="$start" -v b="$end" 'BEGIN { print b - a }')" "$(cut -d' ' -f1-3 /proc/loadavg)"

# The slowest tests (ctest's own log of this run).
echo "slowest tests (s, under ctest -j2):"
awk '/^[0-9]+\/[0-9]+ Test: /{ sub(/^[0-9]+\/[0-9]+ Test: /, ""); name = $0 }
     /^"?Test time = /{ printf "%8.1f  %s\n", $(NF - 1), name }' build/Testing/Temporary/LastTest.log | sort -rn | sed -n 1,15p  # sed reads to the end: head would leave sort a SIGPIPE (pipefail) past 64 KB
if [[ $COSTS == 1 ]]; then
  echo "tests of 1.5 s or more (tests/test_costs.tsv):"
  awk '/^[0-9]+\/[0-9]+ Test: /{ sub(/^[0-9]+\/[0-9]+ Test: /, ""); name = $0 }
       /^"?Test time = /{ t = $(NF - 1); if (t >= 1.5) printf "%.0f\t%s\n", t + 0.5, name }' \
    build/Testing/Temporary/LastTest.log | sort -t$'\t' -k1,1rn
fi
[[ $tests_ok == *" 0 tests failed"* ]]
