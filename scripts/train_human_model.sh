#!/usr/bin/env bash
# A model of the human rig (issue 54, item 1): the shipped A-pose model's
# graph with its encoder reading the body resampled onto the mannequin's
# vertices (graphs/human/drape_grade_v2v1000_post_resampled.yaml: the
# garment's grade on the encoded features, V2V at 1000, TailorNet's push-out
# as the node `post`, and `shape` a resample_body node; drape train
# --encoder-body parametric), trained on the human rig's drapes in each body's
# own size (datasets/bodyspace2000-human, every shard there is), starting from
# every weight of the shipped mannequin model (docs/bodies.md, "One encoder
# for both rigs"). Resumable (drape train --resume); the push-out is set on
# after training, as for the shipped model.
#
#   bash scripts/train_human_model.sh [WORK_DIR]     (default: work-human-model/)
#
# Environment: BUILD_DIR (default build), GRAPH (default
# graphs/human/drape_grade_v2v1000_post_resampled.yaml), INIT (default
# models/tshirt-coarse.h5), THREADS (default 1), EPOCHS (the cosine
# schedule, default 60), LR (default 1e-3), PATIENCE (default 30), SHARD_DIR
# (the folder of slim shards, default datasets/bodyspace2000-human), MIRROR
# (1: the training drapes' mirror images trained on too, scripts/mirror_dataset.py;
# posed shards only; default 0), EXTRA_SHARDS (more slim datasets joined to
# the shards, space-separated, mirrored with them: e.g. the heavy bodies'
# training drapes a second time, scripts/subset_dataset.py; docs/poses.md,
# "Heavy bodies twice"), PUSH_OUT (the push-out's clearance in m stored in
# the model, default 0.006; the shipped posed model's 0.003: docs/poses.md,
# "The penetration margin"), INIT_WIDEN (1: drape train --init-widen, for a
# graph that adds inputs to INIT's: the new weights that read them start at
# zero; docs/poses.md, "More capacity on the human rig"), WEIGHT_DECAY (drape
# train --weight-decay, AdamW's; default 0), MONITOR (drape train
# --monitor: a loss of the graph by name, e.g. v2v, chooses the best epoch
# instead of the weighted total; default the total), MIRROR_AVERAGE (1: the
# model stored with the push-out's mirror_average on, the network's garment
# averaged with its twin's in the mirrored pose; posed models; docs/poses.md,
# "The mirror average").
#
# The shipped A-pose model (since 2026-12-04, twenty-ninth session) is one
# more cycle of the model this makes with the defaults, at the penetration
# margin of 1 mm, the best epoch by V2V, its push-out to 5 mm:
#   GRAPH=graphs/human/drape_grade_v2v1000_post_resampled_margin1mm.yaml INIT=MODEL_OF_BEFORE.h5 \
#     LR=3e-4 EPOCHS=60 MONITOR=v2v PUSH_OUT=0.005 THREADS=2 bash scripts/train_human_model.sh work-human-1mm
# (MODEL_OF_BEFORE.h5: git show 57272c2:models/tshirt-coarse-human.h5 > MODEL_OF_BEFORE.h5).
#
# The posed model of the human rig (issues 54 and 56) is the same recipe on
# the posed shards, from the mannequin's posed model:
#   SHARD_DIR=datasets/posespace2000-human GRAPH=graphs/human/drape_posed_v2v1000_post_resampled.yaml \
#     INIT=models/tshirt-coarse-posed.h5 LR=3e-4 MIRROR=1 bash scripts/train_human_model.sh work-posed-human
# and a further cycle of the shipped posed model (the last of which made it; its decoder input 48 wide,
# its penetration margin 1 mm with the best epoch by V2V, its push-out to 4
# mm, the 450 drapes of seed 5 beside the 2,000):
#   SHARD_DIR=datasets/posespace2000-human GRAPH=graphs/human/drape_posed_v2v1000_post_resampled_transfer48_margin1mm.yaml \
#     INIT=models/tshirt-coarse-posed-human.h5 LR=3e-4 MIRROR=1 PUSH_OUT=0.004 MONITOR=v2v THREADS=2 \
#     EXTRA_SHARDS="$(echo datasets/posespace-human-seed5/shard-*)" bash scripts/train_human_model.sh work-posed-human
# and since the thirtieth session it is stored with the mirror average on
# (MIRROR_AVERAGE=1 above, or drape model set MODEL --set post.mirror_average=true).
# Since the thirty-first session its cycles are trained on ME itself (the
# graph ..._distance.yaml, `--monitor vertex_distance`) with more drapes of
# seeds 5-13 beside the 2,000; each cycle, its data and its figures is a
# section of docs/poses.md, from "Training on the metric" to "Seed 13
# trained on, and shipped" (one not shipped: "Weight decay, and 300 more drapes"). The
# last (the forty-third session), from the model shipped before it
# (`git show 7d9890f:models/tshirt-coarse-posed-human.h5 > shipped.h5`):
#   SHARD_DIR=datasets/posespace2000-human GRAPH=graphs/human/drape_posed_v2v1000_post_resampled_transfer48_margin1mm_distance.yaml \
#     INIT=shipped.h5 LR=3e-4 MIRROR=1 PUSH_OUT=0.005 MONITOR=vertex_distance MIRROR_AVERAGE=1 \
#     THREADS=2 EPOCHS=120 EXTRA_SHARDS="$(echo datasets/posespace-human-seed{5,6,7,8,9,10,11,12,13}/shard-*)" \
#     bash scripts/train_human_model.sh work-posed-human
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
DRAPE=${BUILD_DIR:-build}/bin/drape
WORK=${1:-work-human-model}
mkdir -p "$WORK"
SHARDS=("${SHARD_DIR:-datasets/bodyspace2000-human}"/shard-*-of-40.h5)
# shellcheck disable=SC2206  # (split on spaces by design: a list of paths)
if [[ -n "${EXTRA_SHARDS:-}" ]]; then SHARDS+=(${EXTRA_SHARDS}); fi
DATA="$WORK/human.h5"
# Expanded again when shards were added since; a training interrupted before
# then does not resume on the grown set (drape train --resume compares the
# training and validation counts): use another WORK_DIR.
# What the expanded set was made of: the shard count and the mirror flag.
MADE_OF="${#SHARDS[@]}${MIRROR:+ mirror $MIRROR}${EXTRA_SHARDS:+ extra $EXTRA_SHARDS}"
if [[ ! -f "$DATA" || $(cat "$WORK/shards" 2>/dev/null) != "$MADE_OF" ]]; then
  PARTS=("${SHARDS[@]}")
  if [[ "${MIRROR:-0}" == 1 ]]; then
    # Each training drape's mirror image, in the training split (never a test drape's twin).
    PYTHONPATH="${BUILD_DIR:-build}/python${PYTHONPATH:+:$PYTHONPATH}" /usr/bin/python3 scripts/mirror_dataset.py "${SHARDS[@]}" \
      --split train --out "$WORK/mirrored.h5"
    PARTS+=("$WORK/mirrored.h5")
  fi
  "$DRAPE" dataset expand --force --out "$DATA" "${PARTS[@]}"
  echo "$MADE_OF" >"$WORK/shards"
fi

"$DRAPE" train "${GRAPH:-graphs/human/drape_grade_v2v1000_post_resampled.yaml}" --data "$DATA" --out "$WORK/model.h5" \
  --encoder-body parametric --init "${INIT:-models/tshirt-coarse.h5}" ${INIT_WIDEN:+--init-widen} --epochs "${EPOCHS:-60}" --schedule cosine --lr "${LR:-1e-3}" \
  --patience "${PATIENCE:-30}" ${MONITOR:+--monitor "$MONITOR"} ${WEIGHT_DECAY:+--weight-decay "$WEIGHT_DECAY"} --batch 8 --seed 0 --threads "${THREADS:-1}" --resume
"$DRAPE" model set "$WORK/model.h5" --set post.enabled=true --set post.epsilon="${PUSH_OUT:-0.006}" \
  ${MIRROR_AVERAGE:+--set post.mirror_average=true}

"$DRAPE" eval --model "$WORK/model.h5" --data "$DATA" --split test --out "$WORK/test.csv" --by bmi:10,20,30,45,65
