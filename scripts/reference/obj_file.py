"""An OBJ reader in plain Python and numpy, sharing nothing with drape's mesh
loader, for the reference checks, the figure scripts and the Python tests.
"""
import numpy as np


def read_obj(path):
    """Vertices (float64) and triangles (int64, 0-based) of an OBJ file: polygons
    fanned into triangles; v/vt/vn indices; 1-based or negative (relative) indices."""
    vertices, faces = [], []
    with open(path) as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                vertices.append([float(t) for t in parts[1:4]])
            elif parts[0] == "f":
                ids = [int(t.split("/")[0]) for t in parts[1:]]
                ids = [i - 1 if i > 0 else len(vertices) + i for i in ids]
                faces.extend([ids[0], ids[k], ids[k + 1]] for k in range(1, len(ids) - 1))
    return np.array(vertices, dtype=np.float64), np.array(faces, dtype=np.int64).reshape(-1, 3)
