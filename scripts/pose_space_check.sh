#!/usr/bin/env bash
# Posed bodies over the whole space, checked by code that shares nothing with
# drape's C++: N bodies (default 200) drawn over shape x pose by
# `drape body --sample N --poses`, then for every one scripts/count_self_crossings.py
# (edges through faces, numpy) and a watertightness count (every edge in exactly
# two faces). docs/poses.md reports a run.
#
#   bash scripts/pose_space_check.sh [N] [SEED] [OUT_DIR]
#   BODY_ARGS="--param rig=human" bash scripts/pose_space_check.sh   # another rig or model
set -euo pipefail
cd "$(dirname "$0")/.."
N=${1:-200}
SEED=${2:-1}
OUT=${3:-$(mktemp -d)}
DRAPE=${DRAPE:-build/bin/drape}
start=$(date +%s)
# shellcheck disable=SC2086  # BODY_ARGS is a list of options
nice "$DRAPE" body ${BODY_ARGS:-} --sample "$N" --poses --bmi 10:65 --seed "$SEED" --out-dir "$OUT"
echo "sampled in $(( $(date +%s) - start )) s"
/usr/bin/python3 - "$OUT" <<'PY'
import glob, os, subprocess, sys
import numpy as np
sys.path.insert(0, os.path.join("scripts", "reference"))
from obj_file import read_obj
out = sys.argv[1]
files = sorted(glob.glob(os.path.join(out, "body_*.obj")))
open_edges = 0
for f in files:
    _, faces = read_obj(f)[:2]
    e = np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1)
    _, counts = np.unique(e, axis=0, return_counts=True)
    open_edges += int((counts != 2).sum())
res = subprocess.run([sys.executable, "scripts/count_self_crossings.py", *files], capture_output=True, text=True, check=True)
crossing = [l for l in res.stdout.splitlines() if " 0 edge-face crossings" not in l and "edge-face crossings" in l]
print(f"{len(files)} posed bodies: {open_edges} edges not shared by exactly two faces; "
      f"{len(crossing)} with an edge through a face (count_self_crossings.py)")
for l in crossing[:10]:
    print("  " + l)
sys.exit(1 if open_edges or crossing else 0)
PY
