#!/usr/bin/env python3
"""Count where a triangle mesh passes through itself: an independent check of the self_contact energy.

    /usr/bin/python3 scripts/count_self_crossings.py garment.obj [more.obj ...] [--list 10]

For every mesh edge and every face that shares no vertex with it, the pair counts when the edge's segment
crosses the face's triangle properly (its ends strictly on both sides of the face's plane, and the line through
them strictly inside the face's three edges; touching or coplanar pairs do not count). Prints the number of
such (edge, face) pairs and of the faces involved. A clean surface gives 0; two sheets that pass through each
other along a curve give about two pairs per triangle the curve crosses.

Only numpy (and scripts/reference/obj_file.py), and no code shared with the C++ plugin or the framework (the point of the check): candidates come
from a uniform grid over the edges' and faces' bounding boxes, the test is four orientation determinants.
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "reference"))
from obj_file import read_obj  # noqa: E402  (plain numpy; shares nothing with drape's loader)


def unique_edges(faces):
    e = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    return np.unique(np.sort(e, axis=1), axis=0)


def cell_entries(lo, hi, cell):
    """(cell key, box index) for every grid cell each box [lo, hi] covers."""
    a = np.floor(lo / cell).astype(np.int64)
    b = np.floor(hi / cell).astype(np.int64)
    span = b - a + 1
    keys, owners = [], []
    for dx in range(span[:, 0].max()):
        for dy in range(span[:, 1].max()):
            for dz in range(span[:, 2].max()):
                ok = (dx < span[:, 0]) & (dy < span[:, 1]) & (dz < span[:, 2])
                c = a[ok] + np.array([dx, dy, dz])
                keys.append((c[:, 0] * 73856093) ^ (c[:, 1] * 19349663) ^ (c[:, 2] * 83492791))
                owners.append(np.nonzero(ok)[0])
    return np.concatenate(keys), np.concatenate(owners)


def candidate_pairs(v, edges, faces):
    """(edge, face) pairs whose boxes share a grid cell, without duplicates."""
    elo, ehi = np.minimum(v[edges[:, 0]], v[edges[:, 1]]), np.maximum(v[edges[:, 0]], v[edges[:, 1]])
    ftri = v[faces]
    flo, fhi = ftri.min(axis=1), ftri.max(axis=1)
    cell = 2.0 * np.median(np.linalg.norm(v[edges[:, 0]] - v[edges[:, 1]], axis=1))
    ek, eo = cell_entries(elo, ehi, cell)
    fk, fo = cell_entries(flo, fhi, cell)
    order = np.argsort(fk, kind="stable")
    fk, fo = fk[order], fo[order]
    start = np.searchsorted(fk, ek, side="left")
    count = np.searchsorted(fk, ek, side="right") - start
    rep_e = np.repeat(eo, count)
    offsets = np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)
    rep_f = fo[np.repeat(start, count) + offsets]
    pairs = np.unique(np.stack([rep_e, rep_f], axis=1), axis=0)
    # Boxes must really overlap (a shared hashed cell is only a hint).
    e, f = pairs[:, 0], pairs[:, 1]
    ok = np.all((elo[e] <= fhi[f]) & (flo[f] <= ehi[e]), axis=1)
    return pairs[ok]


def orient(a, b, c, d):
    return np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a))


def crossings(v, faces):
    """The (edge, face) pairs where an edge passes through a face sharing no vertex with it."""
    edges = unique_edges(faces)
    pairs = candidate_pairs(v, edges, faces)
    e, f = edges[pairs[:, 0]], faces[pairs[:, 1]]
    shared = np.zeros(len(pairs), dtype=bool)
    for i in range(2):
        for j in range(3):
            shared |= e[:, i] == f[:, j]
    pairs, e, f = pairs[~shared], e[~shared], f[~shared]
    p, q = v[e[:, 0]], v[e[:, 1]]
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    sp, sq = orient(a, b, c, p), orient(a, b, c, q)
    straddles = sp * sq < 0
    s1, s2, s3 = orient(p, q, a, b), orient(p, q, b, c), orient(p, q, c, a)
    inside = ((s1 > 0) & (s2 > 0) & (s3 > 0)) | ((s1 < 0) & (s2 < 0) & (s3 < 0))
    return pairs[straddles & inside], edges


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("meshes", nargs="+", help="OBJ files")
    parser.add_argument("--list", type=int, default=0, help="print the first N crossing pairs")
    args = parser.parse_args()
    for path in args.meshes:
        v, faces = read_obj(path)
        hits, edges = crossings(v, faces)
        print(f"{path}: {len(v)} vertices, {len(faces)} faces: {len(hits)} edge-face crossings, "
              f"{len(np.unique(hits[:, 1]))} faces crossed")
        for edge, face in hits[: args.list]:
            print(f"  edge {edges[edge].tolist()} through face {face} {faces[face].tolist()}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
