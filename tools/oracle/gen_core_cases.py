#!/usr/bin/env python3
"""Independent expected values for the §2 and §4 ids of `refray formula`.

Each case is computed here from the definitions with numpy (numpy.linalg for inverses,
determinants and solves; numpy.cross; trigonometry in float64), not with refray's code, and
written as one JSON line {"id", "in", "expect", "source"} to tests/data/formula_cases_core.jsonl.
tests/test_formula.c runs every case through refray's formula registry and compares each expected
field to 1e-12 relative (with an absolute floor of 1e-14 for values that are zero in exact
arithmetic). Python is needed only to regenerate the file:

    python3 tools/oracle/gen_core_cases.py > tests/data/formula_cases_core.jsonl
"""
import json
import math
import sys

import numpy as np

rng = np.random.default_rng(20261122)
cases = []


def add(fid, inputs, expect, source="numpy float64 from the definition"):
    cases.append({"id": fid, "in": inputs, "expect": expect, "source": source})


def tolist(x):
    return np.asarray(x, dtype=float).tolist()


def rx(p):
    c, s = math.cos(p), math.sin(p)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def ry(p):
    c, s = math.cos(p), math.sin(p)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def rz(p):
    c, s = math.cos(p), math.sin(p)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def rvec(n, scale=10.0):
    return rng.uniform(-scale, scale, n)


def rad(d):
    return d * math.pi / 180.0


# ---- §2.1 length, dot, cross, triangle-normal
for n in (2, 3, 4):
    for _ in range(4):
        a = rvec(n)
        add("length", {"a": tolist(a)}, {"length": float(np.linalg.norm(a)), "unit": tolist(a / np.linalg.norm(a))})
add("length", {"a": [3, 4]}, {"length": 5.0, "unit": [0.6, 0.8]}, "by hand: 3-4-5 triangle")
add("length", {"a": [0, 0, 0]}, {"length": 0.0, "unit": None}, "by hand: zero vector has no unit vector")
for n in (2, 3, 4):
    for _ in range(4):
        a, b = rvec(n), rvec(n)
        cosang = np.dot(a, b) / np.linalg.norm(a) / np.linalg.norm(b)
        add("dot", {"a": tolist(a), "b": tolist(b)},
            {"dot": float(np.dot(a, b)), "angle_deg": math.degrees(math.acos(cosang))},
            "numpy dot; angle by acos (well conditioned for these random cases)")
add("dot", {"a": [1, 0, 0], "b": [0, 1, 0]}, {"dot": 0.0, "angle_deg": 90.0}, "by hand")
add("dot", {"a": [1, 1], "b": [-1, -1]}, {"dot": -2.0, "angle_deg": 180.0}, "by hand")
add("dot", {"a": [1, 2, 3], "b": [0, 0, 0]}, {"dot": 0.0, "angle_deg": None}, "by hand: no angle with a zero vector")
for _ in range(6):
    a, b = rvec(3), rvec(3)
    x = np.cross(a, b)
    add("cross", {"a": tolist(a), "b": tolist(b)},
        {"cross": tolist(x), "sin_phi": float(np.linalg.norm(x) / np.linalg.norm(a) / np.linalg.norm(b))})
add("cross", {"a": [1, 0, 0], "b": [0, 1, 0]}, {"cross": [0, 0, 1], "sin_phi": 1.0}, "by hand: x cross y = z")
add("cross", {"a": [1, 2], "b": [3, 4]}, {"cross": [0, 0, -2], "sin_phi": 2 / math.sqrt(5 * 25)}, "by hand: 2D embedded with z = 0")
for _ in range(5):
    a, b, c = rvec(3), rvec(3), rvec(3)
    nr = np.cross(b - a, c - a)
    add("triangle-normal", {"a": tolist(a), "b": tolist(b), "c": tolist(c)},
        {"n_raw": tolist(nr), "n": tolist(nr / np.linalg.norm(nr)), "area": float(np.linalg.norm(nr) / 2)})
add("triangle-normal", {"a": [0, 0, 0], "b": [2, 0, 0], "c": [0, 2, 0]},
    {"n_raw": [0, 0, 4], "n": [0, 0, 1], "area": 2.0}, "by hand")

# ---- §2.2 line-point, plane-point
for n in (2, 3):
    for t in (-0.5, 0.0, 0.3, 1.0, 2.5):
        p, q = rvec(n), rvec(n)
        add("line-point", {"p": tolist(p), "q": tolist(q), "t": t},
            {"point": tolist(p + t * (q - p)), "on_ray": t >= 0, "on_segment": 0 <= t <= 1})
for (s, t) in ((0.25, 0.5), (1.5, 0.2), (-0.1, 0.9), (1.0, 0.0)):
    p, q, r = rvec(3), rvec(3), rvec(3)
    add("plane-point", {"p": tolist(p), "q": tolist(q), "r": tolist(r), "s": s, "t": t},
        {"point": tolist(p + s * (q - p) + t * (r - p)), "in_parallelogram": 0 <= s <= 1 and 0 <= t <= 1})

# ---- §2.3 basis-coordinates
for n in (2, 3, 4):
    for _ in range(3):
        B = rng.uniform(-3, 3, (n, n))
        v = rvec(n)
        coords = np.linalg.solve(B.T, v)
        add("basis-coordinates", {"basis": tolist(B), "v": tolist(v)},
            {"coords": tolist(coords), "orthogonal": False, "orthonormal": False}, "numpy.linalg.solve")
R = rz(0.3) @ ry(-0.7) @ rx(1.1)
v = np.array([1.0, -2.0, 0.5])
add("basis-coordinates", {"basis": tolist(R.T), "v": tolist(v)},
    {"coords": tolist(R.T @ v), "orthogonal": True, "orthonormal": True},
    "orthonormal basis = columns of a rotation R: the coordinates are the projections <b_i, v> = R^T v")
add("basis-coordinates", {"basis": [[2, 0], [0, 3]], "v": [4, 9]},
    {"coords": [2, 3], "orthogonal": True, "orthonormal": False}, "by hand")

# ---- §2.4 barycentric
def oriented_area(a, b, c, n):
    return np.dot(np.cross(b - a, c - a), n) / 2


for _ in range(6):
    p1, p2, p3 = rvec(3), rvec(3), rvec(3)
    w = rng.uniform(-0.5, 1.0, 3)
    w /= w.sum()
    q = w[0] * p1 + w[1] * p2 + w[2] * p3
    n = np.cross(p2 - p1, p3 - p1)
    whole = oriented_area(p1, p2, p3, n)
    l = [oriented_area(q, p2, p3, n) / whole, oriented_area(p1, q, p3, n) / whole,
         oriented_area(p1, p2, q, n) / whole]
    add("barycentric", {"p1": tolist(p1), "p2": tolist(p2), "p3": tolist(p3), "q": tolist(q)},
        {"l1": l[0], "l2": l[1], "l3": l[2], "inside": bool(min(l) >= 0)},
        "numpy oriented areas along the triangle normal")
add("barycentric", {"p1": [0, 0], "p2": [4, 0], "p3": [0, 4], "q": [1, 1]},
    {"l1": 0.5, "l2": 0.25, "l3": 0.25, "inside": True}, "by hand: areas 4, 2, 2 of 8")
add("barycentric", {"p1": [0, 0], "p2": [4, 0], "p3": [0, 4], "q": [4, 4]},
    {"l1": -1.0, "l2": 1.0, "l3": 1.0, "inside": False}, "by hand")

# ---- §4.2 2D matrices
for sx, sy in ((2, 3), (-1, 0.5)):
    M = np.diag([sx, sy]).astype(float)
    add("scale2", {"sx": sx, "sy": sy, "point": [1.5, -2]}, {"matrix": tolist(M), "point": tolist(M @ [1.5, -2])})
add("shear2", {"axis": "x", "s": 0.5, "point": [1, 2]}, {"matrix": [[1, 0.5], [0, 1]], "point": [2, 2]}, "by hand")
add("shear2", {"axis": "y", "s": 0.5, "point": [1, 2]}, {"matrix": [[1, 0], [0.5, 1]], "point": [1, 2.5]}, "by hand")
add("reflect2", {"axis": "x", "point": [3, 4]}, {"matrix": [[-1, 0], [0, 1]], "point": [-3, 4]}, "by hand")
add("reflect2", {"axis": "y"}, {"matrix": [[1, 0], [0, -1]]}, "by hand")
for phi in (30.0, 90.0, -135.0, 217.5):
    c, s = math.cos(rad(phi)), math.sin(rad(phi))
    M = np.array([[c, -s], [s, c]])
    add("rotate2", {"phi_deg": phi, "point": [2, 1]}, {"matrix": tolist(M), "point": tolist(M @ [2, 1])})

# ---- §4.3 rotations
for axis, f in (("x", rx), ("y", ry), ("z", rz)):
    for phi in (30.0, -72.0):
        add("rotate3", {"axis": axis, "phi_deg": phi, "point": [1, 2, 3]},
            {"matrix": tolist(f(rad(phi))), "point": tolist(f(rad(phi)) @ [1, 2, 3])})
for order in ("zyx", "xyz", "zxz", "zyz"):
    for (psi, th, phi) in ((30.0, 45.0, 60.0), (-10.0, 80.0, 170.0)):
        a, b, c = rad(psi), rad(th), rad(phi)
        M = {"zyx": rz(c) @ ry(b) @ rx(a), "xyz": rx(a) @ ry(b) @ rz(c),
             "zxz": rz(c) @ rx(b) @ rz(a), "zyz": rz(c) @ ry(b) @ rz(a)}[order]
        add("euler", {"psi_deg": psi, "theta_deg": th, "phi_deg": phi, "order": order}, {"matrix": tolist(M)},
            "numpy product of the elementary rotations in the named order")
R = rz(0.4) @ ry(1.2) @ rx(-0.3)
add("rotation-basis", {"u": tolist(R[0]), "v": tolist(R[1]), "w": tolist(R[2])}, {"matrix": tolist(R), "orthonormal": True})
add("rotation-basis", {"u": [1, 0, 0], "v": [0, 2, 0], "w": [0, 0, 1]},
    {"matrix": [[1, 0, 0], [0, 2, 0], [0, 0, 1]], "orthonormal": False}, "by hand")


def rodrigues(d, phi):
    d = np.asarray(d, float) / np.linalg.norm(d)
    K = np.array([[0, -d[2], d[1]], [d[2], 0, -d[0]], [-d[1], d[0], 0]])
    return np.eye(3) + math.sin(phi) * K + (1 - math.cos(phi)) * K @ K


for d, phi in (([1, 1, 1], 120.0), ([0.3, -0.5, 0.8], 33.0), ([1, 0, 0], 40.0), ([-2, 0, 0], 40.0), ([0, 0, 5], -90.0)):
    dn = np.asarray(d, float) / np.linalg.norm(d)
    if dn[1] == 0 and dn[2] == 0:
        e = np.cross([0, 1, 0], dn)
        e /= np.linalg.norm(e)
    else:
        e = np.array([0, -dn[2], dn[1]]) / math.hypot(dn[1], dn[2])
    f = np.cross(dn, e)
    M = rodrigues(d, rad(phi))
    add("axis-angle", {"d": d, "phi_deg": phi, "point": [1, 2, 3]},
        {"matrix": tolist(M), "e": tolist(e), "f": tolist(f), "point": tolist(M @ [1, 2, 3])},
        "Rodrigues' formula (matrix); e, f from the script's construction (helper y axis when d_y = d_z = 0)")

# ---- §4.4 inverse
for n in (2, 3, 4):
    for _ in range(3):
        A = rng.uniform(-5, 5, (n, n))
        add("inverse", {"matrix": tolist(A)},
            {"inverse": tolist(np.linalg.inv(A)), "singular": False, "det": float(np.linalg.det(A))},
            "numpy.linalg.inv / det (LAPACK)")
add("inverse", {"matrix": [[2, 0, 0], [0, 4, 0], [0, 0, 8]], "kind": "scale"},
    {"inverse": [[0.5, 0, 0], [0, 0.25, 0], [0, 0, 0.125]], "singular": False, "det": 64.0}, "by hand: S(1/x,1/y,1/z)")
R4 = np.eye(4)
R4[:3, :3] = rz(0.5) @ rx(0.25)
add("inverse", {"matrix": tolist(R4), "kind": "rotation"}, {"inverse": tolist(R4.T), "singular": False, "det": 1.0},
    "R^-1 = R^T")
add("inverse", {"matrix": [[1, 0, 0, 3], [0, 1, 0, -4], [0, 0, 1, 5], [0, 0, 0, 1]], "kind": "translation"},
    {"inverse": [[1, 0, 0, -3], [0, 1, 0, 4], [0, 0, 1, -5], [0, 0, 0, 1]], "singular": False, "det": 1.0}, "by hand: T(-x,-y,-z)")

# ---- §4.5 homogeneous, affine, rotate-about-point
add("homogeneous", {"point": [2, 3]}, {"h": [2, 3, 1], "dehomogenised": [2, 3], "at_infinity": False}, "by hand")
add("homogeneous", {"point": [2, 3, 4], "w": 2}, {"h": [4, 6, 8, 2], "dehomogenised": [2, 3, 4], "at_infinity": False}, "by hand")
add("homogeneous", {"direction": [2, 3]}, {"h": [2, 3, 0], "dehomogenised": None, "at_infinity": True}, "by hand")
add("homogeneous", {"h": [6, 3, 3]}, {"h": [6, 3, 3], "dehomogenised": [2, 1], "at_infinity": False}, "by hand")
for n in (2, 3):
    A, b, x = rng.uniform(-3, 3, (n, n)), rvec(n), rvec(n)
    H = np.eye(n + 1)
    H[:n, :n] = A
    H[:n, n] = b
    add("affine", {"a": tolist(A), "b": tolist(b), "x": tolist(x)}, {"y": tolist(A @ x + b), "matrix_h": tolist(H)})
for c, phi in (([2, 1], 90.0), ([-1.5, 4], 33.0)):
    T = np.array([[1, 0, c[0]], [0, 1, c[1]], [0, 0, 1]])
    Tn = np.array([[1, 0, -c[0]], [0, 1, -c[1]], [0, 0, 1]])
    Rh = np.eye(3)
    Rh[:2, :2] = rz(rad(phi))[:2, :2]
    M = T @ Rh @ Tn
    p = M @ [3, 1, 1]
    add("rotate-about-point", {"c": c, "phi_deg": phi, "point": [3, 1]}, {"matrix": tolist(M), "point": tolist(p[:2])})

# ---- §4.6 homogeneous 3D
P = np.array([1.0, -2.0, 3.0, 1.0])
M = np.diag([2.0, 3.0, -1.0, 1.0])
add("scale3h", {"sx": 2, "sy": 3, "sz": -1, "point": [1, -2, 3]}, {"matrix": tolist(M), "point": tolist((M @ P)[:3])})
M = np.eye(4); M[0, 2] = 0.5; M[1, 2] = -2
add("shear3z", {"dx": 0.5, "dy": -2, "point": [1, -2, 3]}, {"matrix": tolist(M), "point": tolist((M @ P)[:3])})
for axis, f in (("x", rx), ("y", ry), ("z", rz)):
    M = np.eye(4); M[:3, :3] = f(rad(25.0))
    add("rotate3h", {"axis": axis, "phi_deg": 25.0, "point": [1, -2, 3]}, {"matrix": tolist(M), "point": tolist((M @ P)[:3])})
M = np.eye(4); M[:3, 3] = [4, 5, -6]
add("translate3h", {"dx": 4, "dy": 5, "dz": -6, "point": [1, -2, 3]}, {"matrix": tolist(M), "point": [5, 3, -3]}, "by hand")

# ---- §4.7 change-of-basis, camera-transform
for n in (2, 3):
    e, B = rvec(n), rng.uniform(-2, 2, (n, n))  # rows of B are the basis vectors
    p = rvec(n)
    T = np.eye(n + 1); T[:n, n] = e
    Bh = np.eye(n + 1); Bh[:n, :n] = B.T
    M = T @ Bh
    add("change-of-basis", {"origin": tolist(e), "basis": tolist(B), "point": tolist(p), "direction": "to-world"},
        {"matrix": tolist(M), "point": tolist((M @ np.append(p, 1))[:n])})
    Mi = np.linalg.inv(M)
    add("change-of-basis", {"origin": tolist(e), "basis": tolist(B), "point": tolist(p), "direction": "to-local"},
        {"matrix": tolist(Mi), "point": tolist((Mi @ np.append(p, 1))[:n])}, "numpy.linalg.inv of the to-world matrix")
for eye, target, up in (([0, 2.6, 7], [0, 0.6, 0], [0, 1, 0]), ([3, -1, 2], [0.5, 0.5, -1], [0.2, 1, 0.1])):
    eye, target, up = (np.asarray(v, float) for v in (eye, target, up))
    w = (eye - target) / np.linalg.norm(eye - target)
    u = np.cross(up, w); u /= np.linalg.norm(u)
    v = np.cross(w, u)
    V = np.eye(4); V[:3, :3] = np.array([u, v, w]); V[:3, 3] = -np.array([u, v, w]) @ eye
    add("camera-transform", {"eye": tolist(eye), "target": tolist(target), "up": tolist(up)},
        {"u": tolist(u), "v": tolist(v), "w": tolist(w), "view": tolist(V)})

# ---- transform-point / -direction / -normal
for _ in range(3):
    M = rng.uniform(-2, 2, (4, 4)); M[3] = [0, 0, 0, 1]
    x = rvec(3)
    add("transform-point", {"matrix": tolist(M), "x": tolist(x)}, {"y": tolist((M @ np.append(x, 1))[:3]), "w": 1.0})
    add("transform-direction", {"matrix": tolist(M), "x": tolist(x)}, {"y": tolist((M @ np.append(x, 0))[:3]), "w": 0.0})
Mp = rng.uniform(-2, 2, (4, 4)); x = rvec(3)
h = Mp @ np.append(x, 1)
add("transform-point", {"matrix": tolist(Mp), "x": tolist(x)}, {"y": tolist(h[:3] / h[3]), "w": float(h[3])},
    "numpy: projective matrix, divided by w")
M3 = rng.uniform(-2, 2, (3, 3)); x = rvec(3)
add("transform-point", {"matrix": tolist(M3), "x": tolist(x)}, {"y": tolist(M3 @ x)}, "a 3x3 matrix on a 3D vector is linear")
for A in (np.diag([2.0, 1.0, 1.0]), rng.uniform(-2, 2, (3, 3)), 3.0 * (rz(0.7) @ rx(0.2)), rz(0.7) @ ry(-1.1)):
    n = rvec(3)
    nn = np.linalg.inv(A).T @ n
    s = A @ n
    ata = A.T @ A
    lam = np.trace(ata) / 3
    sim = bool(np.allclose(ata, lam * np.eye(3), rtol=0, atol=1e-12 * lam))
    orth = bool(np.allclose(ata, np.eye(3), rtol=0, atol=1e-12))
    add("transform-normal", {"matrix": tolist(A), "n": tolist(n)},
        {"n": tolist(nn / np.linalg.norm(nn)), "similarity": sim, "orthogonal": orth,
         "n_shortcut": tolist(s / np.linalg.norm(s))}, "numpy inv(M)^T n, normalised")

for c in cases:
    print(json.dumps(c))
print(f"{len(cases)} cases", file=sys.stderr)
