#!/usr/bin/env bash
# One writer per output (docs/formats.md), checked from outside: two parts.
#
# 1. Race: two identical jobs on one output started at the same instant,
#    ROUNDS times (default 20) for generate, train, optimize and dataset
#    merge, without flags. Whatever the timing, exactly one may run: the
#    other finds the output locked ("is in use") or, if the first has
#    already ended, the output there ("exists"; a generate of the same
#    request then has "nothing to do" and exits 0, simulating nothing). The
#    output must load and the lock file must be gone with its job.
# 2. Held lock: while the lock is held, every command is refused with
#    exit 2 and "is in use" whatever its flags (--force, --resume), and the
#    output is not touched. The holder is flock(1) for each command (no
#    timing involved), then a real `drape train`: the lock is seen held from
#    outside while it runs, the refusal names its pid, and after it is killed
#    (-9) the lock is free again.
#    (Racing two --force jobs would not test this: when the first has ended
#    before the second starts, both running is the right outcome.)
#
# Prints one line per check; exits 1 if any broke the rule.
# tests/cli/two_writers_cli_test.cpp runs it with 3 rounds.
#   scripts/two_writers.sh [ROUNDS]      (from the repository root, after the build)
set -uo pipefail
ROUNDS=${1:-20}
DRAPE=${DRAPE:-$PWD/build/bin/drape}
WORK=$(mktemp -d)
holder=
trap '[[ -n $holder ]] && kill -9 $holder 2>/dev/null; rm -rf "$WORK"' EXIT
export DRAPE_CACHE_DIR=$WORK/cache
cat > "$WORK/tiny.yaml" <<'YAML'
body: {model: parametric}
garment: {template: tshirt, params: {resolution: 300}}
effects: {gravity: {}, stretching: {}, bending: {}}
solver: {morph_steps: 2, settle_steps: 3}
YAML
"$DRAPE" generate "$WORK/tiny.yaml" --count 4 --bmi 15:30 --seed 3 --shard 0/2 --out "$WORK/s0.h5" >/dev/null 2>&1 || exit 1
"$DRAPE" generate "$WORK/tiny.yaml" --count 4 --bmi 15:30 --seed 3 --shard 1/2 --out "$WORK/s1.h5" >/dev/null 2>&1 || exit 1
"$DRAPE" dataset merge --out "$WORK/d.h5" "$WORK/s0.h5" "$WORK/s1.h5" >/dev/null || exit 1

# The outputs' own readers say whether a file is valid.
dataset_valid() { "$DRAPE" dataset info "$1" >/dev/null 2>&1; }
model_valid() { "$DRAPE" model info "$1" >/dev/null 2>&1; }
mesh_valid() { [[ $(grep -c '^f ' "$1" 2>/dev/null) -gt 0 ]]; }

GENERATE=("$DRAPE" generate "$WORK/tiny.yaml" --count 4 --bmi 15:30 --seed 5 --threads 1 --out OUT)
TRAIN=("$DRAPE" train graphs/examples/mlp_baseline.yaml --data "$WORK/d.h5" --epochs 3 --threads 1 -q --out OUT)
OPTIMIZE=("$DRAPE" optimize --scene graphs/scenes/tshirt_coarse.yaml --bmi 30 --iters 3 --out OUT)
MERGE=("$DRAPE" dataset merge "$WORK/s0.h5" "$WORK/s1.h5" --out OUT)

broken=0
# race NAME CHECK EXT COMMAND...: COMMAND (OUT stands for the output) twice at once.
race() {
  local name=$1 check=$2 ext=$3
  shift 3
  local ok=0 both_ran=0 both_refused=0 invalid=0
  for ((r = 0; r < ROUNDS; r++)); do
    local out="$WORK/$name$r.$ext" go="$WORK/go-$name$r"
    local cmd=("${@//OUT/$out}")
    # The starting gun: both jobs wait in read(2) on a FIFO this shell holds
    # open (O_RDWR: no open blocks, and the data stays until both have read),
    # then both lines are written at once. Blocked, not spinning: a busy wait
    # here took a core from the jobs it was timing.
    mkfifo "$go"
    exec 7<>"$go"
    (exec 7>&-; read -r _ <"$go"; "${cmd[@]}" >"$WORK/a.log" 2>&1; echo $? >"$WORK/a.rc") &
    (exec 7>&-; read -r _ <"$go"; "${cmd[@]}" >"$WORK/b.log" 2>&1; echo $? >"$WORK/b.rc") &
    sleep 0.2
    printf 'go\ngo\n' >&7
    wait
    exec 7>&-
    local a b
    a=$(cat "$WORK/a.rc") b=$(cat "$WORK/b.rc")
    if [[ $a$b == 02 || $a$b == 20 ]]; then
      local refused="$WORK/b.log"
      [[ $a == 2 ]] && refused="$WORK/a.log"
      if $check "$out" && [[ ! -e $out.lock ]] && grep -qE "is in use|exists" "$refused" && ! grep -q corrupt "$refused"; then
        ok=$((ok + 1))
      else
        invalid=$((invalid + 1)); echo "round $r of $name: $(cat "$refused")" >&2
      fi
    elif [[ $a$b == 00 ]] && grep -q "nothing to do" "$WORK/a.log" "$WORK/b.log" && $check "$out" && [[ ! -e $out.lock ]]; then
      ok=$((ok + 1))  # the second found the first's finished output, made by the same request: nothing to do (generate)
    elif [[ $a$b == 00 ]]; then both_ran=$((both_ran + 1))
    else both_refused=$((both_refused + 1)); echo "round $r of $name: exits $a $b: $(cat "$WORK/a.log" "$WORK/b.log")" >&2; fi
  done
  printf 'race %-10s %d rounds: one ran and one was refused with a valid output %d, both ran %d, neither ran %d, output invalid or message wrong %d\n' \
    "$name" "$ROUNDS" "$ok" "$both_ran" "$both_refused" "$invalid"
  [[ $ok == "$ROUNDS" ]] || broken=1
}

race generate dataset_valid h5 "${GENERATE[@]}"
race train model_valid h5 "${TRAIN[@]}"
race optimize mesh_valid obj "${OPTIMIZE[@]}"
race merge dataset_valid h5 "${MERGE[@]}"

# held NAME EXT FLAGS COMMAND...: with <out>.lock held by flock(1), COMMAND FLAGS must be refused
# (exit 2, "is in use") and leave the output as it was (absent, or the bytes of a first run).
# The holder is this shell itself (fd 9).
held() {
  local name=$1 ext=$2 flags=$3
  shift 3
  local out="$WORK/held-$name.$ext"
  local cmd=("${@//OUT/$out}")
  exec 9<>"$out.lock"  # this shell holds the lock: no process to stop afterwards
  flock -x 9
  local before=absent
  [[ -e $out ]] && before=$(md5sum <"$out")
  # shellcheck disable=SC2086  # FLAGS is a list of words
  "${cmd[@]}" $flags >"$WORK/held.log" 2>&1
  local rc=$? after=absent
  [[ -e $out ]] && after=$(md5sum <"$out")
  exec 9>&-
  local verdict=refused
  if [[ $rc != 2 ]] || ! grep -q "is in use" "$WORK/held.log" || [[ $before != "$after" ]]; then
    verdict="NOT refused (exit $rc, output $([[ $before == "$after" ]] && echo untouched || echo changed)): $(head -c 400 "$WORK/held.log")"
    broken=1
  fi
  printf 'held %-10s %-9s %s\n' "$name" "${flags:-(none)}" "$verdict"
}

held generate h5 "" "${GENERATE[@]}"
held train h5 "" "${TRAIN[@]}"
"${TRAIN[@]//OUT/$WORK/held-train.h5}" >/dev/null 2>&1  # a finished model for --force and --resume to overwrite
held train h5 --force "${TRAIN[@]}"
held train h5 --resume "${TRAIN[@]}"
held optimize obj "" "${OPTIMIZE[@]}"
held merge h5 "" "${MERGE[@]}"
"${MERGE[@]//OUT/$WORK/held-merge.h5}" >/dev/null 2>&1
held merge h5 --force "${MERGE[@]}"

# A real drape job as the holder: a long training, seen holding its lock from outside.
"$DRAPE" train graphs/examples/mlp_baseline.yaml --data "$WORK/d.h5" --epochs 100000 --threads 1 -q --out "$WORK/long.h5" >/dev/null 2>&1 &
holder=$!
verdict="holds its lock, refuses a --force second writer naming its pid, and frees the lock when killed"
for ((i = 0; i < 3000; i++)); do  # until the lock is taken (at most 30 s)
  [[ -e $WORK/long.h5.lock ]] && ! flock -n "$WORK/long.h5.lock" true && break
  sleep 0.01
done
if flock -n "$WORK/long.h5.lock" true; then
  verdict="did not hold its lock while running"; broken=1
else
  "${TRAIN[@]//OUT/$WORK/long.h5}" --force >"$WORK/held.log" 2>&1
  rc=$?
  if [[ $rc != 2 ]] || ! grep -q "is in use.*pid $holder" "$WORK/held.log"; then
    verdict="second writer not refused with the holder's pid (exit $rc): $(head -c 400 "$WORK/held.log")"; broken=1
  fi
  kill -9 $holder; wait $holder 2>/dev/null; holder=
  if ! flock -n "$WORK/long.h5.lock" true; then verdict="lock still held after its job was killed"; broken=1; fi
fi
printf 'held %-10s a running train %s\n' train "$verdict"
exit $broken
