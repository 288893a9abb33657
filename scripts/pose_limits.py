#!/usr/bin/env python3
"""Where linear blend skinning makes the parametric body pass through itself:
for each body and each joint angle alone (both sides), the furthest angle
`drape body --pose` accepts, by bisection to 1 degree, and the body's volume
change at a few poses (skinning loses volume at bent joints). docs/poses.md
reports a run.

    /usr/bin/python3 scripts/pose_limits.py [--drape build/bin/drape]
"""
import argparse
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "reference"))
from obj_file import read_obj  # noqa: E402

import numpy as np  # noqa: E402

ANGLES = [  # name, rest (accepted), far end of the range of motion
    ("shoulder_abduction", 60, 0), ("shoulder_abduction", 60, 180),
    ("shoulder_rotation", 0, -90), ("shoulder_rotation", 0, 70),
    ("elbow_flexion", 0, 150), ("hip_flexion", 0, 120), ("hip_abduction", 0, -30),
    ("knee_flexion", 0, 135), ("spine_flexion", 0, 80), ("spine_twist", 0, 45),
]
BODIES = [("M BMI 10", "--bmi 10 --sex 1"), ("M BMI 20", "--bmi 20 --sex 1"), ("M BMI 30", "--bmi 30 --sex 1"),
          ("F BMI 45", "--bmi 45 --sex 0 --height 1.6"), ("M BMI 65", "--bmi 65 --sex 1")]


def accepted(drape, body, pose, out):
    r = subprocess.run([drape, "body", *body.split(), "--pose", pose, "--out", out], capture_output=True, text=True)
    return r.returncode == 0


def volume(path):
    v, f = read_obj(path)[:2]
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    return np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--drape", default="build/bin/drape")
    args = ap.parse_args()
    tmp = tempfile.mkdtemp()
    out = os.path.join(tmp, "b.obj")
    print("| body | " + " | ".join(f"{n} {'max' if far > ok else 'min'}" for n, ok, far in ANGLES) + " |")
    print("|---|" + "---:|" * len(ANGLES))
    for label, body in BODIES:
        row = []
        for name, ok, far in ANGLES:
            if accepted(args.drape, body, f"{name}={far}", out):
                row.append(f"{far} (all)")
                continue
            lo, hi = ok, far  # lo accepted, hi refused
            while abs(hi - lo) > 1:
                mid = round((lo + hi) / 2)
                if accepted(args.drape, body, f"{name}={mid}", out):
                    lo = mid
                else:
                    hi = mid
            row.append(str(lo))
        print(f"| {label} | " + " | ".join(row) + " |", flush=True)
    print()
    print("| body | " + " | ".join(p for p in ["shoulder_abduction=90", "elbow_flexion=90", "elbow_flexion=110",
                                                  "shoulder_rotation=-60", "knee_flexion=90"]) + " |")
    print("|---|" + "---:|" * 5)
    for label, body in BODIES:
        subprocess.run([args.drape, "body", *body.split(), "--out", out], capture_output=True, check=True)
        v0 = volume(out)
        row = []
        for pose in ["shoulder_abduction=90", "elbow_flexion=90", "elbow_flexion=110", "shoulder_rotation=-60",
                     "knee_flexion=90"]:
            # Measured on accepted poses only (a refused pose writes nothing).
            if accepted(args.drape, body, pose, out):
                row.append(f"{(volume(out) - v0) * 1e6:+.0f} cm3 ({100 * (volume(out) / v0 - 1):+.2f} %)")
            else:
                row.append("refused")
        print(f"| {label} | " + " | ".join(row) + " |", flush=True)


if __name__ == "__main__":
    main()
