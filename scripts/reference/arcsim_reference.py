#!/usr/bin/env python3
"""Reference values of ArcSim's cloth energies, from ArcSim's own definitions.

An independent re-implementation, in plain Python, of what ArcSim 0.3 does
(src/dde.cpp: evaluate_stretching_sample, stretching_stiffness,
bending_stiffness; src/physics.cpp: stretching_energy, bending_energy), written
from ArcSim's source and sharing nothing with drape's C++. It prints the
energies of one triangle and one hinge that tests/energies/arcsim_reference_test.cpp
compares drape with. Run: python3 scripts/reference/arcsim_reference.py

Conventions (docs/materials.md): ArcSim's solver integrates the stress
s(G) = A(k(G)) G, A = [[k_uu, k_uv, 0], [k_uv, k_vv, 0], [0, 0, 2 k_shear]]
(stretching_force: the shear term doubled against stretching_energy). Once k
depends on G no energy has that stress as its gradient; drape's energy is the
work it does along the straight strain path from rest, printed as W (computed
here by a 20,000-interval midpoint rule, independently of drape's quadrature)
together with the stress itself (s) for stretches along u and v. Likewise
for bending: ArcSim's force freezes k_b(theta), and W is its work from the
flat rest (the same midpoint rule), dW/dtheta the force. E is
stretching_energy at G with the force's shear (2 k_shear G_uv^2), drape's
energy before 2026-11-26; E_energy_fn is stretching_energy as written
(k_shear G_uv^2). Bending takes |theta| for the curvature (ArcSim's signed
theta is printed too, as E_signed).
"""
import math

# ArcSim's materials/gray-interlock.json
DENSITY = 0.187
STRETCHING = [
    [16.593832, -14.695990, 34.477123, 36.860302],
    [46.364765, 53.694656, 261.013855, -29.691301],
    [49.285110, 87.596100, 206.373993, 22.768457],
    [123.989220, 105.181770, 365.966217, 44.217571],
    [139.686325, 73.592560, 413.553162, -174.43853],
    [127.443810, 85.848587, 405.872833, 32.238411],
]
BENDING = [
    [23.191698e-6, 32.932217e-6, 34.406498e-6, 39.014420e-6, 23.382786e-6],
    [24.749964e-6, 18.651314e-6, 16.370552e-6, 25.095791e-6, 8.860165e-6],
    [14.267624e-6, 7.052906e-6, 14.515154e-6, 24.665127e-6, 19.383726e-6],
]
NSAMPLES = 30


def sample(G00, G11, G01):
    # conf.cpp parse(StretchingSamples): d[0][i] = row 0, d[1][i] = row i + 1
    d = [[STRETCHING[0]] * 5, [STRETCHING[i + 1] for i in range(5)]]
    a, b, dd = 2 * G00 + 1, 2 * G01, 2 * G11 + 1  # G*2 + I
    det = math.sqrt(4 * b * b + (a - dd) ** 2)
    l1, l2 = 0.5 * (a + dd + det), 0.5 * (a + dd - det)
    if b:
        v0, v1 = l1 - dd, b
        vn = math.sqrt(v0 * v0 + b * b)
        V = (v0 / vn, v1 / vn)
    elif a >= dd:
        V = (1.0, 0.0)
    else:
        V = (0.0, 1.0)
    w0 = math.sqrt(l1)
    aw = abs(math.atan2(V[1], V[0]) / math.pi) * 8
    aw = min(max(aw, 0), 4 - 1e-6)
    aid = int(aw)
    aw -= aid
    sv = (w0 - 1) * 6
    sv = min(max(sv, 0), 1 - 1e-6)
    sid = 0
    sw = sv - sid
    k = [d[sid][aid][l] * (1 - sw) * (1 - aw) + d[sid + 1][aid][l] * sw * (1 - aw)
         + d[sid][aid + 1][l] * (1 - sw) * aw + d[sid + 1][aid + 1][l] * sw * aw for l in range(4)]
    return [2 * max(x, 0) for x in k]


_grid = {}


def grid(i, j, k):
    if (i, j, k) not in _grid:
        _grid[(i, j, k)] = sample(-0.25 + i / NSAMPLES, -0.25 + j / NSAMPLES, k / NSAMPLES)
    return _grid[(i, j, k)]


def stiffness(G00, G11, G01):
    def coord(t):
        t = min(max(t, 0.0), NSAMPLES - 1 - 1e-5)
        i = min(max(int(math.floor(t)), 0), NSAMPLES - 2)
        return i, t - i
    ai, a = coord((G00 + 0.25) * NSAMPLES)
    bi, b = coord((G11 + 0.25) * NSAMPLES)
    ci, c = coord(abs(G01) * NSAMPLES)
    k = [0.0] * 4
    for i in range(2):
        for j in range(2):
            for l in range(2):
                w = (a if i else 1 - a) * (b if j else 1 - b) * (c if l else 1 - c)
                s = grid(ai + i, bi + j, ci + l)
                for m in range(4):
                    k[m] += w * s[m]
    return k


def triangle_energy(F, area):
    """F: 2x2 in-plane deformation gradient (the triangle stays in its plane)."""
    C = [[F[0][0] ** 2 + F[1][0] ** 2, F[0][0] * F[0][1] + F[1][0] * F[1][1]],
         [0, F[0][1] ** 2 + F[1][1] ** 2]]
    G00, G11, G01 = 0.5 * (C[0][0] - 1), 0.5 * (C[1][1] - 1), 0.5 * C[0][1]
    k = stiffness(G00, G11, G01)
    base = k[0] * G00 ** 2 + k[2] * G11 ** 2 + 2 * k[1] * G00 * G11
    return area * 0.5 * (base + 2 * k[3] * G01 ** 2), area * 0.5 * (base + k[3] * G01 ** 2), (G00, G11, G01), k


def strain_of(F):
    C00 = F[0][0] ** 2 + F[1][0] ** 2
    C11 = F[0][1] ** 2 + F[1][1] ** 2
    C01 = F[0][0] * F[0][1] + F[1][0] * F[1][1]
    return 0.5 * (C00 - 1), 0.5 * (C11 - 1), 0.5 * C01


def stress(G):
    """The stress ArcSim's solver integrates, s = A(k(G)) G."""
    k = stiffness(*G)
    return (k[0] * G[0] + k[1] * G[1], k[1] * G[0] + k[2] * G[1], 2 * k[3] * G[2])


def work(G, intervals=20000):
    """int_0^1 s(t G) . G dt by the midpoint rule."""
    total = 0.0
    for i in range(intervals):
        t = (i + 0.5) / intervals
        s = stress([t * g for g in G])
        total += sum(a * b for a, b in zip(s, G))
    return total / intervals


def stretch_along(angle_deg, s):
    c, n = math.cos(math.radians(angle_deg)), math.sin(math.radians(angle_deg))
    # F = I + (s - 1) d d^T
    return [[1 + (s - 1) * c * c, (s - 1) * c * n], [(s - 1) * c * n, 1 + (s - 1) * n * n]]


def bending_stiffness(theta, l, area, du):
    curv = theta * l / area
    value = curv / 2 * 0.2
    if value > 4:
        value = 4
    vi = int(value)
    vi = min(max(vi, 0), 3)
    value -= vi
    bias = (math.atan2(du[1], du[0])) * 4 / math.pi
    if bias < 0:
        bias = -bias
    if bias > 4:
        bias = 8 - bias
    if bias > 2:
        bias = 4 - bias
    bi = min(max(int(bias), 0), 1)
    bias -= bi
    ke = (BENDING[bi][vi] * (1 - bias) * (1 - value) + BENDING[bi + 1][vi] * bias * (1 - value)
          + BENDING[bi][vi + 1] * (1 - bias) * value + BENDING[bi + 1][vi + 1] * bias * value)
    return max(ke, 0.0)


def hinge_energy(theta, l, a0, a1, du):
    area = a0 + a1
    shape = l * l / (2 * area)
    ke = bending_stiffness(abs(theta), l, area, du)
    ke_signed = bending_stiffness(theta, l, area, du)
    return ke * shape * theta * theta / 4, ke_signed * shape * theta * theta / 4, ke


def hinge_force(theta, l, a0, a1, du):
    """The magnitude dW/dtheta of ArcSim's bending force (physics.cpp, bending_force: coeff (theta - theta0)
    dtheta / 2 with coeff = bending_coeff, k_b frozen at theta), flat rest, |theta| for the curvature."""
    area = a0 + a1
    return bending_stiffness(abs(theta), l, area, du) * l * l / (2 * area) * theta / 2


def hinge_work(theta, l, a0, a1, du, intervals=20000):
    """The work of ArcSim's bending force from the flat rest to theta, by the midpoint rule."""
    total = 0.0
    for i in range(intervals):
        t = (i + 0.5) / intervals * theta
        total += hinge_force(t, l, a0, a1, du)
    return total * theta / intervals


if __name__ == "__main__":
    area = 0.5 * 0.01 * 0.01  # UV right triangle with 1 cm legs
    print("# triangle, UV legs 1 cm along u and v; E = ArcSim energy with the force's shear")
    for angle in (0.0, 90.0, 45.0, 30.0):
        for s in (1.01, 1.10, 1.17, 1.25):
            E, E_fn, G, k = triangle_energy(stretch_along(angle, s), area)
            W = area * work(G)
            print(f"angle {angle:5.1f} stretch {s:.2f}: W = {W:.12e}  E = {E:.12e}  E_energy_fn = {E_fn:.12e}  "
                  f"G = ({G[0]:.6f}, {G[1]:.6f}, {G[2]:.6f})  k = [{', '.join(f'{x:.6f}' for x in k)}]")
    print("# stress s = A(k(G)) G (N/m) along u and v: G = (g, 0, 0) and (0, g, 0)")
    for g in (0.01, 0.05, 0.1, 0.15, 0.18, 0.25):
        su, sv = stress((g, 0.0, 0.0)), stress((0.0, g, 0.0))
        print(f"g {g:.2f}: s_uu = {su[0]:.12e}  s_vv = {sv[1]:.12e}")
    print("# one sample, ArcSim's evaluate_stretching_sample, at G = (0.1, 0, 0.05)")
    print("sample", [f"{x:.9f}" for x in sample(0.1, 0.0, 0.05)])
    print("# hinge: edge (0,0)-(1 cm, 0) in UV, wings at (0.5 cm, +-1 cm): l = 1 cm, A0 = A1 = 0.5 cm^2")
    l, a = 0.01, 0.5 * 0.01 * 0.01
    for du, name in (((1.0, 0.0), "along u"), ((1.0, 1.0), "45 deg"), ((0.0, 1.0), "along v"), ((1.0, 0.3), "16.7 deg")):
        for theta in (0.05, 0.3, 1.2, -0.05, -0.3, -1.2):
            E, E_signed, ke = hinge_energy(theta, l, a, a, du)
            W, M = hinge_work(theta, l, a, a, du), hinge_force(theta, l, a, a, du)
            print(f"edge {name:8s} theta {theta:+.2f}: W = {W:.12e}  dW/dtheta = {M:.12e}  E = {E:.12e}  "
                  f"E_signed = {E_signed:.12e}  k_b = {ke:.9e}")
