#!/bin/bash
# Queues a drape job array and the merge that follows it:
#   scripts/cluster/submit.sh generate SHARDS    (settings of generate.sbatch in the environment)
#   scripts/cluster/submit.sh optimize SHARDS    (settings of optimize.sbatch)
# e.g. COUNT=20000 SEED=1 OUT=/scratch/tshirt.h5 scripts/cluster/submit.sh generate 100
# Extra sbatch options (partition, account, cpus) go in SBATCH_OPTIONS, e.g.
# SBATCH_OPTIONS="--partition=cpu --cpus-per-task=8". Prints the two job ids.
set -euo pipefail
usage="usage: $0 generate|optimize SHARDS"
stage=${1:?$usage}
shards=${2:?$usage}
[[ "$stage" == generate || "$stage" == optimize ]] || { echo "$0: unknown stage '$stage': $usage" >&2; exit 2; }
[[ "$shards" =~ ^[1-9][0-9]*$ ]] || { echo "$0: SHARDS must be a positive number, got '$shards'" >&2; exit 2; }
: "${OUT:?OUT (the merged dataset to make) is required}"
# What the stage's tasks require, checked before anything is queued (a
# missing COUNT, DATA or SCENE was queued, and every task of the array failed).
if [[ "$stage" == generate ]]; then
  : "${COUNT:?COUNT (samples in the whole set) is required for generate}"
else
  : "${DATA:?DATA (the dataset to optimise) is required for optimize}"
  : "${SCENE:?SCENE (the scene of the potential) is required for optimize}"
fi
here=$(cd "$(dirname "$0")" && pwd)
# (${extra[@]+...} below: an empty array under set -u aborts bash before 4.4, e.g. RHEL 7's 4.2.)
read -r -a extra <<< "${SBATCH_OPTIONS:-}"
array=$(sbatch --parsable ${extra[@]+"${extra[@]}"} --array="0-$((shards - 1))" --export="ALL,SHARDS=$shards" "$here/$stage.sbatch")
array=${array%%;*}  # "id;cluster" on federated clusters
merge=$(sbatch --parsable ${extra[@]+"${extra[@]}"} --dependency="afterok:$array" --export="ALL,SHARDS=$shards" "$here/merge.sbatch")
echo "queued $stage array job $array ($shards tasks) and merge job ${merge%%;*} into $OUT"
