#!/usr/bin/env bash
# Two jobs on one output started at the same instant, ROUNDS times (default
# 20) for generate, train, optimize and dataset merge: each round must end
# with one job done (exit 0), the other refused (exit 2), and an output that
# loads, the refused one saying the output is in use (or exists, when the
# other had already finished). Prints one line per command; exits 1 if any
# round broke the rule. tests/cli/two_writers_cli_test.cpp runs it with 3 rounds.
#   scripts/two_writers.sh [ROUNDS]      (from the repository root, after the build)
set -uo pipefail
ROUNDS=${1:-20}
DRAPE=${DRAPE:-$PWD/build/bin/drape}
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
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

# race NAME CHECK EXT SECOND_FLAG COMMAND...: COMMAND (OUT stands for the output) twice at once, the second
# with SECOND_FLAG added (--force where the command has it: the flag that would rewrite a running job's file).
broken=0
race() {
  local name=$1 check=$2 ext=$3 flag=$4
  shift 4
  local ok=0 both_ran=0 both_refused=0 invalid=0
  for ((r = 0; r < ROUNDS; r++)); do
    local out="$WORK/$name$r.$ext" go="$WORK/go-$name$r"
    local cmd=("${@//OUT/$out}")
    (while [[ ! -e $go ]]; do :; done; "${cmd[@]}" >"$WORK/a.log" 2>&1; echo $? >"$WORK/a.rc") &
    (while [[ ! -e $go ]]; do :; done; "${cmd[@]}" $flag >"$WORK/b.log" 2>&1; echo $? >"$WORK/b.rc") &
    sleep 0.2
    touch "$go"
    wait
    local a b
    a=$(cat "$WORK/a.rc") b=$(cat "$WORK/b.rc")
    if [[ $a$b == 02 || $a$b == 20 ]]; then
      # Refused while the other ran, or after it ended (the output then exists); never "corrupt";
      # the lock file gone with the job that held it.
      local refused="$WORK/b.log"
      [[ $a == 2 ]] && refused="$WORK/a.log"
      if $check "$out" && [[ ! -e $out.lock ]] && grep -qE "is in use|exists" "$refused" && ! grep -q corrupt "$refused"; then
        ok=$((ok + 1))
      else
        invalid=$((invalid + 1)); echo "round $r of $name: $(cat "$refused")" >&2
      fi
    elif [[ $a$b == 00 ]]; then both_ran=$((both_ran + 1))
    else both_refused=$((both_refused + 1)); fi
  done
  printf '%-14s %d rounds: one ran and one was refused with a valid output %d, both ran %d, neither ran %d, output invalid or message wrong %d\n' \
    "$name" "$ROUNDS" "$ok" "$both_ran" "$both_refused" "$invalid"
  [[ $ok == "$ROUNDS" ]] || broken=1
}

race generate dataset_valid h5 "" "$DRAPE" generate "$WORK/tiny.yaml" --count 4 --bmi 15:30 --seed 5 --threads 1 --out OUT
race train model_valid h5 --force "$DRAPE" train graphs/examples/mlp_baseline.yaml --data "$WORK/d.h5" --epochs 3 --threads 1 -q --out OUT
race optimize mesh_valid obj "" "$DRAPE" optimize --scene graphs/scenes/tshirt_coarse.yaml --bmi 30 --iters 3 --out OUT
race merge dataset_valid h5 --force "$DRAPE" dataset merge "$WORK/s0.h5" "$WORK/s1.h5" --out OUT
exit $broken
