#!/usr/bin/env bash
# A model of the MakeHuman T-shirt on MakeHuman bodies (issue 22, "a model
# trained on a few hundred drapes predicts with p <= 1 % on held-out
# MakeHuman bodies"; docs/garments.md has the figures). Needs the CC0
# MakeHuman data (../shared/assets/makehuman or $DRAPE_MAKEHUMAN_DIR); the
# model is not shipped, this script makes it. Every step is resumable: run it
# again after a kill and it continues where it stopped.
#
#   bash scripts/train_makehuman_model.sh [WORK_DIR]     (default: work/)
#
# 300 drapes (810-vertex shirt, 13,380-vertex body) of both sexes, heights
# 1.62-1.88 m and BMI 15-32 (where MakeHuman reaches for every sex and height
# drawn) take ~20 minutes on 2 cores; the seed's model on them a few minutes.
# Environment: COUNT (default 300), BUILD_DIR (default build), THREADS
# (default all cores).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
DRAPE=${BUILD_DIR:-build}/bin/drape
WORK=${1:-work}
THREADS=${THREADS:-$(nproc)}
COUNT=${COUNT:-300}
DATA="$WORK/makehuman$COUNT.h5"
mkdir -p "$WORK"

# Split 80/10/10 % into train, validation and test by the seed.
"$DRAPE" generate graphs/scenes/makehuman_tshirt.yaml --count "$COUNT" --bmi 15:32 --height 1.62:1.88 --sex 0:1 \
  --seed 7 --out "$DATA" --threads "$THREADS"
"$DRAPE" train graphs/drape.yaml --data "$DATA" --out "$WORK/makehuman-drape.h5" --epochs 100 --batch 8 --lr 1e-3 \
  --schedule cosine --patience 20 --seed 0 --threads "$THREADS" --resume
"$DRAPE" eval --model "$WORK/makehuman-drape.h5" --data "$DATA" --split test \
  --out "$WORK/makehuman-drape-test.csv" --svg "$WORK/makehuman-drape-errors.svg"
