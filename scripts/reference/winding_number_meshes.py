#!/usr/bin/env python3
"""p (percent of garment vertices inside the body) of written drapes, by the
generalized winding number of winding_number.py, reading the OBJ files with
obj_file.py: nothing of drape's is used (no mesh loader, no inside
test), so it checks `drape simulate --out G.obj --body-out B.obj` from outside.

    /usr/bin/python3 scripts/reference/winding_number_meshes.py G1.obj B1.obj [G2.obj B2.obj ...]
"""
import sys

from obj_file import read_obj
from winding_number import winding_numbers


def main():
    paths = sys.argv[1:]
    if not paths or len(paths) % 2:
        sys.exit(__doc__)
    worst = 0.0
    for garment_path, body_path in zip(paths[::2], paths[1::2]):
        garment, _ = read_obj(garment_path)
        body, body_faces = read_obj(body_path)
        w = winding_numbers(body, body_faces, garment)
        p = 100.0 * (w > 0.5).mean()
        worst = max(worst, p)
        print("%s on %s: p = %.3f %% (%d of %d vertices inside; largest winding number %.3f)" %
              (garment_path, body_path, p, int((w > 0.5).sum()), len(garment), w.max()), flush=True)
    print("largest p %.3f %%" % worst)


if __name__ == "__main__":
    main()
