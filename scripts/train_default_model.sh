#!/usr/bin/env bash
# How models/tshirt-coarse.h5 (the pretrained model `drape predict` uses by
# default) was made, and the comparison with the L2-trained MLP baseline
# reported in docs/training.md. Every step is resumable: run the script again
# after a kill and it continues where it stopped.
#
#   bash scripts/train_default_model.sh [WORK_DIR]     (default: work/)
#
# About an hour on 2 cores: 1000 coarse drapes (~40 min), then the two
# trainings and their evaluations. Environment: BUILD_DIR (default build),
# EPOCHS (default 60), THREADS (default all cores).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
DRAPE=${BUILD_DIR:-build}/bin/drape
WORK=${1:-work}
EPOCHS=${EPOCHS:-60}
THREADS=${THREADS:-$(nproc)}
mkdir -p "$WORK"

# 1000 drapes of the coarse T-shirt (991 vertices) on bodies of BMI 10-65:
# 800 train, 100 validation, 100 test.
"$DRAPE" generate graphs/scenes/tshirt_coarse.yaml --count 1000 --bmi 10:65 --seed 1 \
  --out "$WORK/coarse1000.h5" --threads "$THREADS"

train() {  # graph, model file
  "$DRAPE" train "$1" --data "$WORK/coarse1000.h5" --out "$2" --epochs "$EPOCHS" --batch 8 --lr 1e-3 \
    --schedule cosine --patience 15 --seed 0 --threads "$THREADS" --resume
}
train graphs/drape.yaml "$WORK/drape.h5"
train graphs/baselines/mlp_l2.yaml "$WORK/mlp_l2.h5"

for model in drape mlp_l2; do
  "$DRAPE" eval --model "$WORK/$model.h5" --data "$WORK/coarse1000.h5" --split test --out "$WORK/$model-test.csv"
done
echo "the model to ship: cp $WORK/drape.h5 models/tshirt-coarse.h5"
