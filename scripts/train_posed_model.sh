#!/usr/bin/env bash
# The shipped model of posed drapes, models/tshirt-coarse-posed.h5 (issue 56,
# docs/poses.md "The shipped model of posed drapes"): the shipped sized
# A-pose model's graph taken to poses by unposing
# (graphs/poses/drape_posed_sized.yaml: encoder on the body at rest, the
# pose's angles appended after the grade, the skin node to the pose),
# started from models/tshirt-coarse.h5 (--init-widen: the angles' weights at
# zero, so it begins as the A-pose drape posed by the garment's skinning) and
# trained on the shape x pose drapes of datasets/posespace2000 in cosine
# cycles (warm restarts), then evaluated on their test split and on the
# held-out poses. Resumable (drape train --resume; a finished cycle is kept).
#
#   bash scripts/train_posed_model.sh [WORK_DIR]      (default: work-posed-model/)
#
# Environment: BUILD_DIR (default build), DATA (default every shard of
# datasets/posespace2000), HELDOUT (default
# datasets/posespace-heldout/heldout-30.h5), THREADS (default 1), EPOCHS
# (each cycle's cosine schedule, default 100), LR (default 1e-3), PATIENCE
# (default 30),
# SCHEDULE: one word per cosine cycle, each cycle from the one before,
#   `posed` for graphs/poses/drape_posed_sized.yaml and `v2v100` for
#   graphs/poses/drape_posed_sized_v2v100.yaml (the same graph, L_V2V at 100
#   instead of 10). Default "posed posed posed v2v100 posed": three cycles,
#   one that lets the distance win over the physics terms, and one more to
#   take the penetration back (docs/poses.md, "Closing the ME gap on posed
#   drapes"). CYCLES=N is SCHEDULE of N `posed` words (the recipe before).
# INIT: the first cycle's start (default models/tshirt-coarse.h5, the A-pose
#   model, widened; a posed model continues as it is).
# The shipped model is two runs of this script: shards 0-16 with
#   SCHEDULE="posed posed posed" and INIT the A-pose model of 450 sized drapes
#   (`git show 54d1804^:models/tshirt-coarse.h5`, shipped until the seventh
#   session of 2026-11-30), then INIT=<that model.h5> with
#   SCHEDULE="posed v2v100 posed" on shards 0-27, then SCHEDULE=posed EPOCHS=60
#   on shards 0-31 and the thin set, then one cycle of
#   graphs/poses/drape_posed_sized_v2v100_post.yaml on shards 0-33 and the
#   thin set and `drape model set ... --set post.enabled=true --set
#   post.epsilon=0.006` (the push-out on; docs/poses.md, "Since the ninth
#   session", gives the commands), then one 40-epoch cycle of
#   graphs/poses/drape_posed_sized_v2v1000_post.yaml on all 40 shards and
#   the thin set, the push-out set on again (docs/poses.md, "Since the tenth
#   session").
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
DRAPE=${BUILD_DIR:-build}/bin/drape
WORK=${1:-work-posed-model}
DATA=${DATA:-datasets/posespace2000/shard-*-of-40.h5}
HELDOUT=${HELDOUT:-datasets/posespace-heldout/heldout-30.h5}
if [ -n "${CYCLES:-}" ]; then
  [[ "$CYCLES" =~ ^[1-9][0-9]*$ ]] || { echo "train_posed_model.sh: CYCLES must be a count of cycles, got '$CYCLES'" >&2; exit 2; }
  SCHEDULE=$(for ((k = 0; k < CYCLES; k++)); do printf 'posed '; done)
fi
read -r -a cycles <<< "${SCHEDULE:-posed posed posed v2v100 posed}"
[ "${#cycles[@]}" -gt 0 ] || { echo "train_posed_model.sh: SCHEDULE names no cycle" >&2; exit 2; }
graph_of() {
  case "$1" in
    posed) echo graphs/poses/drape_posed_sized.yaml ;;
    v2v100) echo graphs/poses/drape_posed_sized_v2v100.yaml ;;
    *) echo "train_posed_model.sh: SCHEDULE: unknown cycle '$1' (posed, v2v100)" >&2; return 2 ;;
  esac
}
for c in "${cycles[@]}"; do graph_of "$c" > /dev/null || exit 2; done  # every word checked before any training
mkdir -p "$WORK"
init=(--init "${INIT:-models/tshirt-coarse.h5}" --init-widen)
for ((k = 0; k < ${#cycles[@]}; k++)); do
  graph=$(graph_of "${cycles[$k]}")
  out="$WORK/cycle$((k + 1)).h5"
  [ "$k" -eq $((${#cycles[@]} - 1)) ] && out="$WORK/model.h5"
  "$DRAPE" train "$graph" --data "$DATA" --out "$out" "${init[@]}" --epochs "${EPOCHS:-100}" --lr "${LR:-1e-3}" \
    --schedule cosine --patience "${PATIENCE:-30}" --batch 8 --seed 0 --threads "${THREADS:-1}" --resume
  init=(--init "$out")
done
"$DRAPE" eval --model "$WORK/model.h5" --data "$DATA" --split test --out "$WORK/test.csv"
"$DRAPE" eval --model "$WORK/model.h5" --data "$HELDOUT" --split all --out "$WORK/heldout.csv"
