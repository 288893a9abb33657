#!/usr/bin/env python3
"""How wide are a drape's folds, in triangles? An independent measure of mesh-scale crinkles.

    /usr/bin/python3 scripts/fold_width.py drape.obj [more.obj ...] [--angle 5] [--json out.json] [--ply out.ply]
    /usr/bin/python3 scripts/fold_width.py --self-test

A fold is a band of cloth bent one way (a ridge, or a valley) between two bands bent the other way; its
width is the distance between the lines where the bending changes sign. A "one-triangle crinkle"
(paper-like zig-zag) is a ridge one row of triangles away from a valley on each side.

The measure:

1. Curvature. Per vertex, the discrete curvature tensor of Cohen-Steiner and Morvan (the normal cycle)
   over the vertex's barycentric cell: T_v = sum over the edges at v of theta_e (|e| / 2) e e^T / A_v,
   theta_e the signed dihedral angle (positive where the surface turns away from its normal: a ridge),
   A_v a third of the area of v's faces. The normal curvature along a tangent direction d is
   b^T T b with b = n x d. The tensor, not the edges' angles one by one: on a triangle mesh bent into
   a smooth cylinder the edges' angles alternate in sign with the edges' directions (an edge along the
   bending direction turns the other way), which would read as a zig-zag; the tensor gives the
   cylinder's 1/R within 0.2 % (checked below).
2. A face is bent when its largest principal curvature |kappa| (the tensor averaged over its corners)
   turns the surface by at least ANGLE (default 5 degrees) over one triangle height h:
   |kappa| h >= ANGLE. h is the face's height, twice its area over its mean edge (an equilateral
   triangle's height; the spacing of parallel rows of edges on a regular mesh).
3. From a bent face's centroid, walk straight across the surface along the principal direction (across
   the fold), both ways, up to MAX triangle heights (default 8): each triangle entered is unfolded into
   the plane of the last (a straightest path, from the mesh's own 3D edge lengths, so it crosses seams
   and needs no UV). Along the walk the normal curvature along the walk (the tensor interpolated
   linearly in each face) is sampled where the walk crosses edges; the walk stops where it changes sign
   (interpolated linearly), at s+ and s-; at a boundary or at MAX there is no neighbouring fold on that
   side (s = MAX h).
4. The fold's width, in triangles, is w = (s+ + s-) / h. A zig-zag (ridge and valley on alternate rows
   of edges) gives w = 1.08 (its curvature changes sign halfway between rows); a sine fold of
   half-wavelength W gives w = W / h to within 10 % (a little more: the walk is measured on the
   slanted surface); a lone cylinder gives w = 2 MAX.

What it prints per mesh:
  * bent: the share of the garment's area in bent faces;
  * crinkled: the share of the bent area (and of all of it) in folds narrower than two triangles
    (w < 2), and their share of the curvature measure sum(kappa^2 A) (the shape of a bending energy);
  * the narrowest fold (min w), and w's 1st, 10th and 50th percentiles over the bent faces.
The target of issue 54 (item 3) is no fold narrower than two triangles: crinkled 0 % and min w >= 2.

Only numpy (and scripts/reference/obj_file.py for reading OBJ); nothing from drape. --self-test checks it on
synthetic sheets of an equilateral triangle lattice: a zig-zag is 100 % crinkled in the interior (w 1.08); sine
folds of half-wavelength 2, 3 and 5 triangle heights, across the lattice's rows, along them and at 17 degrees,
give widths within 0.5 of W / h and none below 2; a cylinder gives no crinkle and its curvature. About 10 s
of one core for a 3,505-vertex drape.
"""
import argparse
import json
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "reference"))
from obj_file import read_obj  # noqa: E402  (plain numpy; shares nothing with drape's loader)


class Hinges:
    """Interior edges of a triangle mesh with their two faces, corners and signed dihedral angles."""

    def __init__(self, x, faces):
        self.x = np.asarray(x, float)
        self.faces = np.asarray(faces, np.int64)
        f = self.faces
        nf = len(f)
        # half-edges (a -> b) of face i, corner k: a = f[i, k], b = f[i, k + 1]
        a = f.reshape(-1)
        b = f[:, [1, 2, 0]].reshape(-1)
        face = np.repeat(np.arange(nf), 3)
        corner = np.tile(np.arange(3), nf)
        key = np.minimum(a, b) * (len(self.x) + 1) + np.maximum(a, b)
        order = np.lexsort((face, key))
        key, face, corner, a, b = key[order], face[order], corner[order], a[order], b[order]
        same = key[1:] == key[:-1]
        if np.any(same[1:] & same[:-1]):
            raise ValueError("an edge is shared by more than two faces: not a manifold surface")
        i = np.nonzero(same)[0]
        if np.any(a[i] == a[i + 1]):
            raise ValueError("two faces of an edge run it the same way: the mesh is not consistently oriented")
        self.face = np.stack([face[i], face[i + 1]], 1)      # [h, 2]
        self.corner = np.stack([corner[i], corner[i + 1]], 1)
        self.a, self.b = a[i], b[i]                           # the edge as face[0] runs it
        self.apex = np.stack([f[self.face[:, 0], (self.corner[:, 0] + 2) % 3],
                              f[self.face[:, 1], (self.corner[:, 1] + 2) % 3]], 1)
        # which hinge lies on each face's corner edge (or -1: a boundary edge)
        self.hinge_of = -np.ones((nf, 3), np.int64)
        self.hinge_of[self.face[:, 0], self.corner[:, 0]] = np.arange(len(i))
        self.hinge_of[self.face[:, 1], self.corner[:, 1]] = np.arange(len(i))
        p = self.x[f]
        n = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
        self.face_area = 0.5 * np.linalg.norm(n, axis=1)
        self.normal = n / np.maximum(2 * self.face_area, 1e-300)[:, None]
        e = self.x[self.b] - self.x[self.a]
        self.length = np.linalg.norm(e, axis=1)
        n0, n1 = self.normal[self.face[:, 0]], self.normal[self.face[:, 1]]
        # signed dihedral angle: positive where the surface turns away from its normal (a ridge)
        self.theta = np.arctan2(np.einsum("ij,ij->i", np.cross(n0, n1), e / self.length[:, None]),
                                np.einsum("ij,ij->i", n0, n1))
        self.height = self.face_area[self.face].sum(1) / self.length   # (A0 + A1) / |e|

    def __len__(self):
        return len(self.theta)


def _exit(p, d, q, skip):
    """Where the ray p + t d leaves the triangle q (3x2) by an edge other than `skip` (-1: any):
    (t, corner k of the edge q[k] -> q[k+1], s along it), or None."""
    best = None
    for k in range(3):
        if k == skip:
            continue
        u, v = q[k], q[(k + 1) % 3]
        ev = v - u
        den = d[0] * ev[1] - d[1] * ev[0]
        if abs(den) < 1e-15:
            continue
        w = u - p
        t = (w[0] * ev[1] - w[1] * ev[0]) / den
        s = (w[0] * d[1] - w[1] * d[0]) / den
        if t > 1e-12 and -1e-9 <= s <= 1 + 1e-9 and (best is None or t < best[0]):
            best = (t, k, s)
    return best


class Curvature:
    """A mesh's discrete curvature tensor per vertex (Cohen-Steiner and Morvan's normal cycle, over the
    vertex's barycentric cell): T_v = sum over the edges at v of theta_e (|e| / 2) e e^T / A_v, A_v a third
    of the area of v's faces. T_v is the shape operator turned by 90 degrees in the tangent plane: the
    normal curvature along a tangent direction d is b^T T b with b = n x d (so a cylinder's hinges, which
    run along its axis, give its curvature across it). Positive: a ridge, as theta."""

    def __init__(self, x, faces):
        hg = Hinges(x, faces)
        self.hinges = hg
        nv = len(hg.x)
        e = (hg.x[hg.b] - hg.x[hg.a]) / hg.length[:, None]
        w = 0.5 * hg.theta * hg.length
        outer = w[:, None, None] * e[:, :, None] * e[:, None, :]
        t = np.zeros((nv, 3, 3))
        np.add.at(t, hg.a, outer)
        np.add.at(t, hg.b, outer)
        area = np.zeros(nv)
        for k in range(3):
            np.add.at(area, hg.faces[:, k], hg.face_area / 3)
        self.tensor = t / np.maximum(area, 1e-300)[:, None, None]
        # a face's height: twice its area over its mean edge (an equilateral triangle's height)
        p = hg.x[hg.faces]
        edge = np.linalg.norm(p[:, [1, 2, 0]] - p, axis=2).mean(1)
        self.face_height = 2 * hg.face_area / np.maximum(edge, 1e-300)

    def normal_curvature(self, f, bary, d3):
        """Curvature along the unit tangent d3 at barycentric point `bary` of face f."""
        hg = self.hinges
        t = np.einsum("k,kij->ij", bary, self.tensor[hg.faces[f]])
        n = hg.normal[f]
        b = np.array([n[1] * d3[2] - n[2] * d3[1], n[2] * d3[0] - n[0] * d3[2], n[0] * d3[1] - n[1] * d3[0]])  # n x d3
        return float(b @ t @ b)


def _face_frame(x, faces, f):
    """Face f laid out in 2D (corner 0 at the origin, corner 1 on the x axis, counter-clockwise)."""
    a, b, c = x[faces[f]]
    lab = np.linalg.norm(b - a)
    lac, lbc = np.linalg.norm(c - a), np.linalg.norm(c - b)
    cx = (lac * lac - lbc * lbc + lab * lab) / (2 * lab)
    return np.array([[0.0, 0.0], [lab, 0.0], [cx, math.sqrt(max(lac * lac - cx * cx, 0.0))]])


def _to_3d(x, faces, f, q):
    """The linear map from face f's 2D layout q to 3D (3x2)."""
    xs = x[faces[f]]
    return np.column_stack([xs[1] - xs[0], xs[2] - xs[0]]) @ _inv2(q[1] - q[0], q[2] - q[0])


def _inv2(c0, c1):
    """The inverse of the 2x2 matrix of columns c0, c1 in closed form: np.linalg.inv costs a LAPACK call
    per face and per step of a walk (OpenBLAS's threads hand it over; 0.1-1.4 ms a call on a busy machine,
    most of --self-test's time)."""
    det = c0[0] * c1[1] - c1[0] * c0[1]
    return np.array([[c1[1], -c1[0]], [-c0[1], c0[0]]]) / det


def _bary(q, p):
    a = np.column_stack([q[1] - q[0], q[2] - q[0]])
    l12 = np.linalg.solve(a, p - q[0])
    return np.array([1 - l12.sum(), l12[0], l12[1]])


def _walk(cv, f, q, p, d, sign, limit, k0):
    """Walk straight from point p of face f (layout q) along the 2D direction d; the distance at which the
    normal curvature along the walk changes sign from `sign` (linearly interpolated), or None within
    `limit` or at the boundary. k0: the curvature at p (times sign: positive)."""
    hg = cv.hinges
    x, faces = hg.x, hg.faces
    prev_s, prev_k = 0.0, k0
    travelled = 0.0
    skip = -1
    for _ in range(100000):
        hit = _exit(p, d, q, skip)
        if hit is None:
            return None
        t, ke, s = hit
        s = min(max(s, 1e-6), 1 - 1e-6)     # through a vertex: pass just beside it
        u, v = q[ke], q[(ke + 1) % 3]
        p = u + s * (v - u)
        travelled += t
        m = _to_3d(x, faces, f, q)
        d3 = m @ d
        d3 /= math.sqrt(d3 @ d3)  # = np.linalg.norm, without its overhead per step
        bary = np.zeros(3)
        bary[ke], bary[(ke + 1) % 3] = 1 - s, s
        k = cv.normal_curvature(f, bary, d3) * sign
        if k <= 0.0:
            zero = prev_s + (travelled - prev_s) * prev_k / (prev_k - k) if prev_k > k else travelled
            return zero
        if travelled > limit:
            return None
        prev_s, prev_k = travelled, k
        g = hg.hinge_of[f, ke]
        if g < 0:
            return None          # the boundary: no neighbouring fold on this side
        other = 1 if hg.face[g, 0] == f else 0
        f2, k2 = hg.face[g, other], hg.corner[g, other]
        # face f2 runs the edge the other way (v -> u): unfold its apex across the edge
        i2c = faces[f2, (k2 + 2) % 3]
        iu, iv = faces[f, ke], faces[f, (ke + 1) % 3]
        cu, cv_ = x[i2c] - x[iu], x[i2c] - x[iv]
        luc, lvc = math.sqrt(cu @ cu), math.sqrt(cv_ @ cv_)
        ev = v - u
        luv = math.sqrt(ev @ ev)
        ev = ev / luv
        along = (luc * luc - lvc * lvc + luv * luv) / (2 * luv)
        off = math.sqrt(max(luc * luc - along * along, 0.0))
        c2 = u + along * ev + off * np.array([ev[1], -ev[0]])   # right of u -> v, away from f's apex
        q2 = np.zeros((3, 2))
        q2[k2], q2[(k2 + 1) % 3], q2[(k2 + 2) % 3] = v, u, c2
        f, q, skip = f2, q2, k2
    return None


def fold_widths(x, faces, angle_deg=5.0, max_heights=8.0, only=None):
    """Per face: (Curvature, the largest principal curvature at its centroid, bent mask, width in
    triangles (nan where not bent)). only: a face mask; the others are left unmeasured (not bent)."""
    cv = Curvature(x, faces)
    hg = cv.hinges
    nf = len(faces)
    kappa = np.zeros(nf)
    width = np.full(nf, np.nan)
    bent = np.zeros(nf, bool)
    third = np.full(3, 1.0 / 3.0)
    for f in range(nf) if only is None else np.flatnonzero(only):
        q = _face_frame(hg.x, faces, f)
        m = _to_3d(hg.x, faces, f, q)           # isometric for the first face: columns orthonormal
        t = np.einsum("k,kij->ij", third, cv.tensor[faces[f]])
        t2 = m.T @ t @ m
        lam, vec = np.linalg.eigh(0.5 * (t2 + t2.T))
        i = int(np.argmax(np.abs(lam)))
        kappa[f] = lam[i]
        if abs(lam[i]) * cv.face_height[f] < math.radians(angle_deg):
            continue
        bent[f] = True
        b = vec[:, i]
        d = np.array([-b[1], b[0]])             # across the fold: perpendicular to b in the plane
        p = q.mean(0)
        limit = max_heights * cv.face_height[f]
        s = []
        for direction in (d, -d):
            r = _walk(cv, f, q, p, direction, math.copysign(1.0, lam[i]), limit, abs(lam[i]))
            s.append(limit if r is None else r)
        width[f] = (s[0] + s[1]) / cv.face_height[f]
    return cv, kappa, bent, width


def summary(x, faces, angle_deg=5.0, max_heights=8.0):
    cv, kappa, bent, width = fold_widths(x, faces, angle_deg, max_heights)
    area = cv.hinges.face_area
    narrow = bent & (width < 2.0)
    measure = kappa ** 2 * area
    w = width[bent]
    pct = (lambda q: float(np.percentile(w, q))) if len(w) else (lambda q: float("nan"))
    out = {
        "vertices": int(len(x)), "faces": int(len(faces)),
        "mean_edge_m": float(cv.hinges.length.mean()), "mean_height_m": float(cv.face_height.mean()),
        "angle_deg": angle_deg,
        "bent_faces": int(bent.sum()), "bent_area_share": float(area[bent].sum() / area.sum()),
        "crinkled_faces": int(narrow.sum()),
        "crinkled_share_of_bent": float(area[narrow].sum() / max(area[bent].sum(), 1e-300)),
        "crinkled_area_share": float(area[narrow].sum() / area.sum()),
        "crinkled_curvature_share": float(measure[narrow].sum() / max(measure.sum(), 1e-300)),
        "narrowest": float(w.min()) if len(w) else float("nan"),
        "p01": pct(1), "p10": pct(10), "median": pct(50),
    }
    return out, cv, bent, width


# ----------------------------------------------------------------------------------------------------------
# synthetic sheets for --self-test


def lattice(nx, ny, s=1.0, rotate_deg=0.0):
    """An equilateral triangle lattice, rows along x, counter-clockwise faces (normal +z)."""
    h = s * math.sqrt(3) / 2
    pts = []
    for j in range(ny):
        for i in range(nx):
            pts.append((i * s + (0.5 * s if j % 2 else 0.0), j * h))
    faces = []
    for j in range(ny - 1):
        for i in range(nx - 1):
            v00, v10 = j * nx + i, j * nx + i + 1
            v01, v11 = (j + 1) * nx + i, (j + 1) * nx + i + 1
            if j % 2 == 0:
                faces += [(v00, v10, v01), (v10, v11, v01)]
            else:
                faces += [(v00, v11, v01), (v00, v10, v11)]
    p = np.array(pts)
    c, sn = math.cos(math.radians(rotate_deg)), math.sin(math.radians(rotate_deg))
    p = p @ np.array([[c, sn], [-sn, c]])
    return np.column_stack([p, np.zeros(len(p))]), np.array(faces), h


def self_test():
    ok = True

    def check(name, cond, detail):
        nonlocal ok
        print(("ok   " if cond else "FAIL ") + name + ": " + detail)
        ok = ok and cond

    def interior(x, faces, radius):
        c = x[:, :2].mean(0)
        return np.linalg.norm(x[faces, :2].mean(1) - c, axis=1) < radius

    x, f, h = lattice(26, 26)
    # zig-zag: alternate rows up and down (ridge, valley, ridge ... one triangle apart)
    z = x.copy()
    z[:, 2] = np.where(np.round(x[:, 1] / h).astype(int) % 2 == 0, 0.3 * h, -0.3 * h)
    r, cv, bent, width = summary(z, f)
    mid = interior(x, f, 6 * h)
    check("zig-zag", np.all(bent[mid]) and np.all(width[mid] < 2.0) and r["crinkled_share_of_bent"] > 0.9,
          f"interior: {100 * np.mean(width[mid] < 2):.1f} % crinkled, widths {np.nanmin(width[mid]):.2f}-"
          f"{np.nanmax(width[mid]):.2f}; whole sheet {100 * r['crinkled_share_of_bent']:.1f} % of the bent area")
    # sine folds of half-wavelength W across the rows, along them, and at angles to the lattice
    for W in (2.0, 3.0, 5.0):
        for direction in (0.0, 90.0, 17.0):
            x2, f2, h2 = lattice(34, 40)
            a = math.radians(direction)
            t = x2[:, 0] * math.sin(a) + x2[:, 1] * math.cos(a)   # across the fold
            lam = 2 * W * h2
            amp = 0.8 * lam / (2 * math.pi)                         # slopes up to about 40 degrees
            y = x2.copy()
            y[:, 2] = amp * np.sin(2 * math.pi * t / lam)
            # Only the interior is checked, so only it is measured (the walks are the cost).
            inner = interior(x2, f2, 6 * h2)
            cv, kappa, bent, width = fold_widths(y, f2, only=inner)
            mid = inner & bent
            wm = width[mid]
            good = np.all(wm >= 2.0) if W >= 3 else abs(np.median(wm) - W) < 0.5
            check(f"sine W={W:g} h at {direction:g} deg", good and abs(np.median(wm) - W) < 0.5,
                  f"interior: widths {wm.min():.2f}-{wm.max():.2f}, median {np.median(wm):.2f} (W/h = {W:g}), "
                  f"{100 * np.mean(wm < 2):.1f} % crinkled")
    # a cylinder (one fold, no neighbour): bent everywhere, nothing narrow; its curvature is 1/R
    x3, f3, h3 = lattice(24, 24)
    R = 4.0
    cyl = np.column_stack([R * np.sin(x3[:, 1] / R), x3[:, 0], R * (1 - np.cos(x3[:, 1] / R))])
    r, cv, bent, width = summary(cyl, f3, angle_deg=5.0)
    mid = interior(x3, f3, 5 * h3)
    tmid = cv.tensor[np.unique(f3[mid])]
    kmax = np.abs(np.linalg.eigvalsh(tmid)).max(1)
    check("cylinder", r["crinkled_faces"] == 0 and np.allclose(kmax * R, 1.0, atol=0.02),
          f"{r['bent_faces']} bent faces, {r['crinkled_faces']} crinkled; interior curvature x R "
          f"{kmax.min() * R:.3f}-{kmax.max() * R:.3f}")
    return ok


def write_ply(path, x, faces, bent, width):
    """Faces coloured by the fold width at their centre: red < 2 triangles, yellow 2-3, grey otherwise."""
    col = np.where(bent & (width < 2), 0, np.where(bent & (width < 3), 1, 2))
    rgb = np.array([[220, 30, 30], [240, 200, 40], [190, 190, 190]])[col]
    with open(path, "w") as out:
        out.write(f"ply\nformat ascii 1.0\nelement vertex {len(x)}\nproperty float x\nproperty float y\n"
                  f"property float z\nelement face {len(faces)}\nproperty list uchar int vertex_indices\n"
                  "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n")
        for v in x:
            out.write(f"{v[0]} {v[1]} {v[2]}\n")
        for fc, c in zip(faces, rgb):
            out.write(f"3 {fc[0]} {fc[1]} {fc[2]} {c[0]} {c[1]} {c[2]}\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("meshes", nargs="*")
    ap.add_argument("--angle", type=float, default=5.0, help="degrees: a hinge bent less is no fold (default 5)")
    ap.add_argument("--max", type=float, default=8.0, help="triangle heights each way the walk looks (default 8)")
    ap.add_argument("--json", help="write the numbers as JSON (a list, one entry per mesh)")
    ap.add_argument("--ply", help="write the (last) mesh with faces coloured by fold width (red: < 2 triangles)")
    ap.add_argument("--self-test", action="store_true", help="check the measure on synthetic sheets")
    args = ap.parse_args()
    if args.self_test:
        sys.exit(0 if self_test() else 1)
    if not args.meshes:
        ap.error("give at least one mesh (or --self-test)")
    rows = []
    for path in args.meshes:
        x, f = read_obj(path)
        r, cv, bent, width = summary(x, f, args.angle, args.max)
        r["mesh"] = path
        rows.append(r)
        print(f"{path}: {r['vertices']} vertices, mean edge {100 * r['mean_edge_m']:.2f} cm; bent "
              f"{100 * r['bent_area_share']:.1f} % of the area; crinkled (fold < 2 triangles): "
              f"{100 * r['crinkled_share_of_bent']:.1f} % of the bent area, {100 * r['crinkled_area_share']:.1f} % "
              f"of all, {100 * r['crinkled_curvature_share']:.1f} % of the curvature; fold width in triangles: "
              f"narrowest {r['narrowest']:.2f}, p01 {r['p01']:.2f}, p10 {r['p10']:.2f}, median {r['median']:.2f}")
        if args.ply:
            write_ply(args.ply, x, f, bent, width)
    if args.json:
        with open(args.json, "w") as out:
            json.dump(rows, out, indent=1)


if __name__ == "__main__":
    main()
