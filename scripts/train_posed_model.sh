#!/usr/bin/env bash
# The shipped model of posed drapes, models/tshirt-coarse-posed.h5 (issue 56,
# docs/poses.md "The shipped model of posed drapes"): the shipped sized
# A-pose model's graph taken to poses by unposing
# (graphs/poses/drape_posed_sized.yaml: encoder on the body at rest, the
# pose's angles appended after the grade, the skin node to the pose),
# started from models/tshirt-coarse.h5 (--init-widen: the angles' weights at
# zero, so it begins as the A-pose drape posed by the garment's skinning) and
# trained on the shape x pose drapes of datasets/posespace2000, then
# evaluated on their test split and on the held-out poses. Resumable (drape
# train --resume).
#
#   bash scripts/train_posed_model.sh [WORK_DIR]      (default: work-posed-model/)
#
# Environment: BUILD_DIR (default build), GRAPH (default
# graphs/poses/drape_posed_sized.yaml), DATA (default every shard of
# datasets/posespace2000), HELDOUT (default
# datasets/posespace-heldout/heldout-30.h5), THREADS (default 1), EPOCHS
# (the cosine schedule, default 100), LR (default 1e-3), PATIENCE (default 30),
# CYCLES (default 3: cosine cycles, each from the last; the first from the
# A-pose model).
# The shipped model is this script's model.h5 with
# DATA='datasets/posespace2000/shard-{0[0-9],1[0-6]}-of-40.h5' (shards 0-16), copied.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
DRAPE=${BUILD_DIR:-build}/bin/drape
WORK=${1:-work-posed-model}
DATA=${DATA:-datasets/posespace2000/shard-*-of-40.h5}
HELDOUT=${HELDOUT:-datasets/posespace-heldout/heldout-30.h5}
GRAPH=${GRAPH:-graphs/poses/drape_posed_sized.yaml}
CYCLES=${CYCLES:-3}
mkdir -p "$WORK"
# Cycle 1 starts from the A-pose model (the angles' rows at zero); each later
# cycle from the one before, the learning rate back at LR (a warm restart:
# docs/poses.md, "What holds the posed model's error"). The last is model.h5.
init=(--init models/tshirt-coarse.h5 --init-widen)
for ((cycle = 1; cycle <= CYCLES; cycle++)); do
  out="$WORK/cycle$cycle.h5"
  [ "$cycle" -eq "$CYCLES" ] && out="$WORK/model.h5"
  "$DRAPE" train "$GRAPH" --data "$DATA" --out "$out" "${init[@]}" --epochs "${EPOCHS:-100}" --lr "${LR:-1e-3}" \
    --schedule cosine --patience "${PATIENCE:-30}" --batch 8 --seed 0 --threads "${THREADS:-1}" --resume
  init=(--init "$out")
done
"$DRAPE" eval --model "$WORK/model.h5" --data "$DATA" --split test --out "$WORK/test.csv"
"$DRAPE" eval --model "$WORK/model.h5" --data "$HELDOUT" --split all --out "$WORK/heldout.csv"
