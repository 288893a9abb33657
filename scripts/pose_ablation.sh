#!/usr/bin/env bash
# Unposing against world-space prediction on drapes over shape x pose
# (issue 56, docs/poses.md): graphs/poses/drape_unposed.yaml (the network in
# the body's rest pose, a skin node to the pose) and drape_world.yaml (the
# same network and angles, posed body in, posed drape out) trained on the same
# drapes with the same settings, each evaluated on the test split and, when
# given, on a held-out set whose poses lie outside the training ones.
#
#   bash scripts/pose_ablation.sh WORK [DATA] [HELDOUT]
#
# DATA: a posed dataset or a quoted glob of its shards (default
# 'datasets/posespace2000/shard-*-of-40.h5'); HELDOUT: a posed dataset of
# other poses (drape generate --poses draw --pose-range ..., all its samples
# evaluated). Environment: BUILD_DIR (default build), EPOCHS (default 300),
# THREADS (default 1), PATIENCE (default 100). Resumable: train --resume.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
DRAPE=${BUILD_DIR:-build}/bin/drape
WORK=${1:?usage: pose_ablation.sh WORK [DATA] [HELDOUT]}
DATA=${2:-datasets/posespace2000/shard-*-of-40.h5}
HELDOUT=${3:-}
mkdir -p "$WORK"
for GRAPH in graphs/poses/drape_unposed.yaml graphs/poses/drape_world.yaml; do
  NAME=$(basename "$GRAPH" .yaml)
  "$DRAPE" train "$GRAPH" --data "$DATA" --out "$WORK/$NAME.h5" --epochs "${EPOCHS:-300}" --batch 8 --lr 1e-3 \
    --schedule cosine --patience "${PATIENCE:-100}" --seed 0 --threads "${THREADS:-1}" --resume
  "$DRAPE" eval --model "$WORK/$NAME.h5" --data "$DATA" --split test --out "$WORK/$NAME-test.csv"
  if [[ -n "$HELDOUT" ]]; then
    "$DRAPE" eval --model "$WORK/$NAME.h5" --data "$HELDOUT" --split all --out "$WORK/$NAME-heldout.csv"
  fi
done
for CSV in "$WORK"/*-test.csv "$WORK"/*-heldout.csv; do
  [[ -f "$CSV" ]] && { echo "== $CSV"; cat "$CSV"; }
done
