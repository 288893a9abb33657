"""Closest points on a triangle mesh by brute force over every face, in numpy
alone (no drape code): what the tests use to check drape's surface attachments
(its BVH searches) from outside. Ericson, Real-Time Collision Detection, 5.1.5.
"""
import numpy as np


def closest_on_triangles(p, a, b, c):
    """Barycentric weights [n, 3] of the closest point of each p[i] on triangle (a[i], b[i], c[i])."""
    ab, ac, ap = b - a, c - a, p - a
    d1, d2 = (ab * ap).sum(1), (ac * ap).sum(1)
    bp = p - b
    d3, d4 = (ab * bp).sum(1), (ac * bp).sum(1)
    cp = p - c
    d5, d6 = (ab * cp).sum(1), (ac * cp).sum(1)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    n = len(p)
    out = np.zeros((n, 3))
    left = np.ones(n, bool)

    def take(mask, u, v, w):
        m = mask & left
        out[m] = np.stack([u, v, w], axis=1)[m]
        left[m] = False

    one, zero = np.ones(n), np.zeros(n)
    with np.errstate(all="ignore"):
        take((d1 <= 0) & (d2 <= 0), one, zero, zero)  # vertex a
        take((d3 >= 0) & (d4 <= d3), zero, one, zero)  # vertex b
        t = d1 / (d1 - d3)
        take((vc <= 0) & (d1 >= 0) & (d3 <= 0), 1 - t, t, zero)  # edge ab
        take((d6 >= 0) & (d5 <= d6), zero, zero, one)  # vertex c
        t = d2 / (d2 - d6)
        take((vb <= 0) & (d2 >= 0) & (d6 <= 0), 1 - t, zero, t)  # edge ac
        t = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        take((va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0), zero, 1 - t, t)  # edge bc
        den = 1 / (va + vb + vc)
        v, w = vb * den, vc * den
        take(np.ones(n, bool), 1 - v - w, v, w)  # inside the face
    return out


def closest_points(vertices, faces, points):
    """For each point: (face index, barycentric weights [3], distance) of its closest point on the mesh, every face tried."""
    a, b, c = vertices[faces[:, 0]], vertices[faces[:, 1]], vertices[faces[:, 2]]
    face = np.zeros(len(points), int)
    bary = np.zeros((len(points), 3))
    dist = np.zeros(len(points))
    for i, p in enumerate(points):
        w = closest_on_triangles(np.broadcast_to(p, a.shape), a, b, c)
        q = w[:, :1] * a + w[:, 1:2] * b + w[:, 2:] * c
        d = np.linalg.norm(q - p, axis=1)
        k = int(np.argmin(d))
        face[i], bary[i], dist[i] = k, w[k], d[k]
    return face, bary, dist
