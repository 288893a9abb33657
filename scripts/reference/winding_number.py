"""The generalized winding number of a closed triangle mesh at points, in numpy
alone (no drape code): 1 inside, 0 outside. What scripts/reference uses to
check drape's inside test (p) from outside.
"""
import numpy as np


def winding_numbers(vertices, faces, points, chunk=64):
    """Van Oosterom-Strackee solid angles summed over the faces, / 4 pi."""
    a_all, b_all, c_all = vertices[faces[:, 0]], vertices[faces[:, 1]], vertices[faces[:, 2]]
    w = np.zeros(len(points))
    for s in range(0, len(points), chunk):
        p = points[s:s + chunk, None]
        a, b, c = a_all[None] - p, b_all[None] - p, c_all[None] - p
        la, lb, lc = (np.linalg.norm(x, axis=2) for x in (a, b, c))
        det = np.einsum("ijk,ijk->ij", a, np.cross(b, c))
        den = (la * lb * lc + np.einsum("ijk,ijk->ij", a, b) * lc + np.einsum("ijk,ijk->ij", b, c) * la +
               np.einsum("ijk,ijk->ij", c, a) * lb)
        w[s:s + chunk] = np.arctan2(det, den).sum(axis=1) / (2 * np.pi)
    return w
