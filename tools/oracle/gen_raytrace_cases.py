#!/usr/bin/env python3
"""Independent expected values for the §3 ids of `refray formula` (ray tracing).

Every expected output is computed here from the definitions in FORMULAS.md (and the lecture
script, with its errata) in mpmath at 50 significant digits, on the exact double inputs that are
written to the file, then rounded once to double. Nothing here uses refray's code or its
algorithms: intersections are solved in the primitive's own frame or by a linear solve, the
stable sphere variant is checked against the exact roots (it must give the same roots), the
triangle variants against the exact barycentric solution, the cone in a local orthonormal frame.

One JSON line per case {"id", "in", "expect", "source"[, "rel", "abs"]} goes to
tests/data/formula_cases_raytrace.jsonl; tests/test_raytrace.c runs each through the registry
and compares every expected field to 1e-12 relative with an absolute floor of 1e-14 (booleans
and nulls exactly). Cases with "error": true must be refused. A case sets its own "rel" only
where the exact answer is ill-conditioned in the input (grazing refraction: sqrt sensitivity).
Python and mpmath are needed only to regenerate the file:

    python3 tools/oracle/gen_raytrace_cases.py > tests/data/formula_cases_raytrace.jsonl
"""
import json
import sys

import mpmath as mp
import numpy as np

mp.mp.dps = 50
rng = np.random.default_rng(3_2026_11_22)
cases = []
MP = "mpmath 50 digits from the definition"


def add(fid, inputs, expect, source=MP, **extra):
    c = {"id": fid, "in": inputs, "expect": expect, "source": source}
    c.update(extra)
    cases.append(c)


def err(fid, inputs, source):
    cases.append({"id": fid, "in": inputs, "expect": {}, "error": True, "source": source})


def F(x):
    return float(x)


def FV(v):
    return [float(x) for x in v]


def M(v):
    return mp.matrix([mp.mpf(float(x)) for x in v])


def dot(a, b):
    return sum(a[i] * b[i] for i in range(3))


def cross(a, b):
    return mp.matrix([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]])


def norm(a):
    return mp.sqrt(dot(a, a))


def unit(a):
    return a / norm(a)


def rv(n=3, s=5.0):
    return [float(x) for x in rng.uniform(-s, s, n)]


def runit():
    while True:
        v = rng.uniform(-1, 1, 3)
        if 0.2 < np.linalg.norm(v) <= 1:
            return [float(x) for x in v / np.linalg.norm(v)]


def rad(deg):
    return mp.mpf(float(deg)) * mp.pi / 180


def deg(r):
    return r * 180 / mp.pi


# ---------------------------------------------------------------- 3.1 nyquist
for fmax, fs in [(100.0, 250.0), (100.0, 200.0), (100.0, 199.0), (0.0, 1.0), (22050.0, 44100.0), (20000.0, 44100.0)]:
    add("nyquist", {"f_max": fmax, "f_sample": fs},
        {"min_rate": 2 * fmax, "aliasing": not (fs > 2 * fmax), "nyquist_frequency": fs / 2},
        "Satz 3.1: the rate must be strictly greater than 2 f_max")
err("nyquist", {"f_max": -1.0, "f_sample": 10.0}, "negative frequency")


# ---------------------------------------------------------------- 3.4 camera-basis, primary-ray
def basis(eye, target, up):
    w = unit(M(eye) - M(target))
    u = unit(cross(M(up), w))  # erratum 3.4: normalised
    v = cross(w, u)
    return u, v, w


for k in range(8):
    eye, target = rv(), rv()
    up = [0.0, 1.0, 0.0] if k < 2 else rv()
    u, v, w = basis(eye, target, up)
    add("camera-basis", {"eye": eye, "target": target, "up": up}, {"u": FV(u), "v": FV(v), "w": FV(w)},
        MP + "; u = up x w normalised (erratum 3.4)")
add("camera-basis", {"eye": [0, 0, 5], "target": [0, 0, 0], "up": [0, 1, 0]},
    {"u": [1, 0, 0], "v": [0, 1, 0], "w": [0, 0, 1]}, "by hand")
add("camera-basis", {"eye": [0, 0, 0], "target": [0, 0, -1], "up": [0, 2, 1]},
    {"u": [1, 0, 0], "v": [0, 1, 0], "w": [0, 0, 1]}, "by hand: up not perpendicular and not unit (erratum 3.4)")
err("camera-basis", {"eye": [0, 0, 0], "target": [0, 1, 0], "up": [0, 3, 0]}, "up parallel to the view direction")
err("camera-basis", {"eye": [1, 1, 1], "target": [1, 1, 1], "up": [0, 1, 0]}, "eye = target")


def primary(inp):
    u, v, w = basis(inp["eye"], inp["target"], inp["up"])
    d = mp.mpf(inp.get("d", 1.0))
    nx, ny = inp["nx"], inp["ny"]
    if "fov_deg" in inp:
        t = d * mp.tan(rad(inp["fov_deg"]) / 2)
        r = t * nx / ny
        l, b = -r, -t
    else:
        l, r, b, t = (mp.mpf(inp[k]) for k in "lrbt")
    sx, sy = mp.mpf(inp.get("sx", 0.5)), mp.mpf(inp.get("sy", 0.5))
    l1 = l + (r - l) * (inp["i"] + sx) / nx
    l2 = t - (t - b) * (inp["j"] + sy) / ny
    s = l1 * u + l2 * v - d * w
    return {"origin": FV(M(inp["eye"])), "s": FV(s), "direction": FV(unit(s)), "l": F(l), "r": F(r), "b": F(b), "t": F(t)}


for k in range(10):
    nx, ny = int(rng.integers(1, 800)), int(rng.integers(1, 600))
    inp = {"eye": rv(), "target": rv(), "up": [0.0, 0.0, 1.0] if k % 2 else [0.0, 1.0, 0.0],
           "nx": nx, "ny": ny, "i": int(rng.integers(0, nx)), "j": int(rng.integers(0, ny))}
    if k % 3 == 0:
        inp["fov_deg"] = float(rng.uniform(10, 120))
        inp["d"] = float(rng.uniform(0.5, 3))
    elif k % 3 == 1:
        inp["fov_deg"] = 60.0
        inp["sx"], inp["sy"] = float(rng.uniform(0, 1)), float(rng.uniform(0, 1))
    else:
        inp.update({"l": -1.5, "r": 0.5, "b": -0.25, "t": 1.0, "d": 2.0})
    add("primary-ray", inp, primary(inp), MP + "; lambda1 = l + (r-l)(i+sx)/nx, lambda2 = t - (t-b)(j+sy)/ny")
add("primary-ray", {"eye": [0, 0, 0], "target": [0, 0, -1], "up": [0, 1, 0], "l": -1, "r": 1, "b": -1, "t": 1,
                    "nx": 2, "ny": 2, "i": 0, "j": 0},
    {"origin": [0, 0, 0], "s": [-0.5, 0.5, -1], "direction": FV(unit(mp.matrix([-0.5, 0.5, -1]))),
     "l": -1, "r": 1, "b": -1, "t": 1}, "by hand: pixel (0,0) is the top-left one")
err("primary-ray", {"eye": [0, 0, 0], "target": [0, 0, -1], "up": [0, 1, 0], "fov_deg": 60, "l": -1, "r": 1,
                    "b": -1, "t": 1, "nx": 2, "ny": 2, "i": 0, "j": 0}, "both fov_deg and l,r,b,t")
err("primary-ray", {"eye": [0, 0, 0], "target": [0, 0, -1], "up": [0, 0, 1], "fov_deg": 60, "nx": 2, "ny": 2,
                    "i": 0, "j": 0}, "up parallel to the view direction")
err("primary-ray", {"eye": [0, 0, 0], "target": [0, 0, -1], "up": [0, 1, 0], "fov_deg": 60, "nx": 2, "ny": 2,
                    "i": 2, "j": 0}, "pixel outside the image")


# ---------------------------------------------------------------- 3.5.1 intersect-sphere
def sphere(inp):
    o, d, c, r = M(inp["origin"]), M(inp["dir"]), M(inp["center"]), mp.mpf(inp["radius"])
    f = o - c
    a, b, cc = dot(d, d), 2 * dot(d, f), dot(f, f) - r * r
    disc = b * b - 4 * a * cc
    out = {"a": F(a), "b": F(b), "c": F(cc), "disc": F(disc)}
    if disc < 0:
        out.update({"t1": None, "t2": None, "t": None, "hit": False, "point": None, "normal": None})
        return out
    t1, t2 = (-b - mp.sqrt(disc)) / (2 * a), (-b + mp.sqrt(disc)) / (2 * a)
    out.update({"t1": F(t1), "t2": F(t2)})
    t = t1 if t1 >= 0 else (t2 if t2 >= 0 else None)
    if t is None:
        out.update({"t": None, "hit": False, "point": None, "normal": None})
    else:
        p = o + t * d
        out.update({"t": F(t), "hit": True, "point": FV(p), "normal": FV((p - c) / r)})
    return out


for variant in ("script", "stable"):
    for k in range(12):
        c = rv()
        r = float(rng.uniform(0.5, 3))
        o = rv(s=10)
        aim = [c[i] + float(rng.uniform(-1.5, 1.5)) * r for i in range(3)]
        d = [aim[i] - o[i] for i in range(3)]
        if k % 4 == 3:
            d = [-x for x in d]  # mostly behind the origin
        inp = {"origin": o, "dir": d, "center": c, "radius": r, "variant": variant}
        ex = sphere(inp)
        # keep well-conditioned cases: clear of tangency
        if abs(ex["disc"]) < 1e-2 * ex["b"] ** 2:
            continue
        add("intersect-sphere", inp, ex, MP + "; roots by the midnight formula in 50 digits")
    for o, exp_t in [([0, 0, -5], 4.0), ([0, 1, -5], 5.0), ([0, 2, -5], None), ([0, 0, 0], 1.0), ([0, 0, 5], None)]:
        inp = {"origin": o, "dir": [0, 0, 1], "center": [0, 0, 0], "radius": 1, "variant": variant}
        ex = sphere(inp)
        assert ex["t"] == exp_t
        add("intersect-sphere", inp, ex, "Ray Tracer Challenge spheres.feature: hit, tangent, miss, inside, behind")
# the stable variant on a far small sphere (reliability.md S1): the exact roots, to 1e-12
for x0 in (0.5, 0.9, 1.5):
    inp = {"origin": [0, 0, 0], "dir": [0, 0, -1], "center": [x0, 0, -1e8], "radius": 1, "variant": "stable"}
    add("intersect-sphere", inp, sphere(inp),
        MP + "; far sphere: b^2 - 4ac cancels in double, the stable form must still give the exact roots")
err("intersect-sphere", {"origin": [0, 0, 0], "dir": [0, 0, 0], "center": [0, 0, 5], "radius": 1}, "zero direction")
err("intersect-sphere", {"origin": [0, 0, 0], "dir": [0, 0, 1], "center": [0, 0, 5], "radius": 0}, "radius 0")


# ---------------------------------------------------------------- 3.5.2 intersect-plane
def plane(inp):
    o, d, n, off = M(inp["origin"]), M(inp["dir"]), M(inp["normal"]), mp.mpf(inp["offset"])
    den = dot(d, n)
    if den == 0:
        return {"parallel": True, "t_line": None, "t": None, "hit": False, "point": None, "normal": None}
    t = (off - dot(o, n)) / den
    out = {"parallel": False, "t_line": F(t)}
    if t >= 0:
        out.update({"t": F(t), "hit": True, "point": FV(o + t * d), "normal": FV(unit(n))})
    else:
        out.update({"t": None, "hit": False, "point": None, "normal": None})
    return out


for k in range(10):
    inp = {"origin": rv(), "dir": rv(), "normal": rv(), "offset": float(rng.uniform(-3, 3))}
    add("intersect-plane", inp, plane(inp), MP + "; Hesse form <x,n> = offset")
add("intersect-plane", {"origin": [0, 0, 0], "dir": [1, 0, 0], "normal": [0, 0, 1], "offset": 2},
    plane({"origin": [0, 0, 0], "dir": [1, 0, 0], "normal": [0, 0, 1], "offset": 2}), "by hand: parallel")
add("intersect-plane", {"origin": [0, 0, 5], "dir": [0, 0, 1], "normal": [0, 0, 1], "offset": 2},
    {"parallel": False, "t_line": -3.0, "t": None, "hit": False}, "by hand: behind the origin")
add("intersect-plane", {"origin": [1, 2, 0], "dir": [0, 0, 2], "normal": [0, 0, 3], "offset": 6},
    {"parallel": False, "t_line": 1.0, "t": 1.0, "hit": True, "point": [1, 2, 2], "normal": [0, 0, 1]},
    "by hand: non-unit normal and direction")
err("intersect-plane", {"origin": [0, 0, 0], "dir": [1, 0, 0], "normal": [0, 0, 0], "offset": 2}, "zero normal (erratum 3.5.2)")


# ---------------------------------------------------------------- 3.5.3 intersect-triangle
def triangle(inp):
    o, d = M(inp["origin"]), M(inp["dir"])
    p1, p2, p3 = M(inp["p1"]), M(inp["p2"]), M(inp["p3"])
    e1, e2 = p2 - p1, p3 - p1
    A = mp.matrix([[d[i], -e1[i], -e2[i]] for i in range(3)])
    miss = {"t": None, "hit": False, "point": None, "normal": None, "l1": None, "l2": None, "l3": None}
    if mp.det(A) == 0:
        return miss
    t, u, v = mp.lu_solve(A, p1 - o)
    if t < 0 or u < 0 or v < 0 or u + v > 1:
        return miss
    return {"t": F(t), "hit": True, "point": FV(o + t * d), "normal": FV(unit(cross(e1, e2))),
            "l1": F(1 - u - v), "l2": F(u), "l3": F(v)}


for variant in ("script", "moller", "watertight"):
    for k in range(10):
        p1, p2, p3 = rv(), rv(), rv()
        a, b = float(rng.uniform(-0.3, 1)), float(rng.uniform(-0.3, 1))
        l = [1 - a - b, a, b]
        if min(l) > -0.02 and min(l) < 0.02:
            continue  # near an edge: only exact edge cases below
        aim = [l[0] * p1[i] + l[1] * p2[i] + l[2] * p3[i] for i in range(3)]
        o = rv(s=15)
        d = [aim[i] - o[i] for i in range(3)]
        inp = {"origin": o, "dir": d, "p1": p1, "p2": p2, "p3": p3, "variant": variant}
        add("intersect-triangle", inp, triangle(inp), MP + "; t, u, v by an exact linear solve")
    base = {"p1": [0, 0, 0], "p2": [1, 0, 0], "p3": [0, 1, 0], "variant": variant}
    for o, d, why in [([0.25, 0.25, 1], [0, 0, -1], "interior"), ([0.25, 0.25, -2], [0, 0, 1], "from the back (two-sided)"),
                      ([0.5, 0, 1], [0, 0, -1], "on the edge p1-p2"), ([0, 0, 1], [0, 0, -1], "on the vertex p1"),
                      ([0.75, 0.75, 1], [0, 0, -1], "outside"), ([0.25, 0.25, 1], [0, 0, 1], "behind the origin"),
                      ([-1, 0.25, 1], [1, 0, 0], "parallel to the plane")]:
        inp = dict(base, origin=o, dir=d)
        add("intersect-triangle", inp, triangle(inp), "by hand (checked in 50 digits): " + why)
err("intersect-triangle", {"origin": [0, 0, 1], "dir": [0, 0, -1], "p1": [0, 0, 0], "p2": [1, 1, 0], "p3": [2, 2, 0]},
    "degenerate triangle")
err("intersect-triangle", {"origin": [0, 0, 1], "dir": [0, 0, 0], "p1": [0, 0, 0], "p2": [1, 0, 0], "p3": [0, 1, 0]},
    "zero direction")


# ---------------------------------------------------------------- NFF intersect-cylinder / intersect-cone
def cone(inp):
    """In a local frame (e1, e2, k) at the base: x^2 + y^2 = (rb + m z)^2, 0 <= z <= H."""
    o, d = M(inp["origin"]), M(inp["dir"])
    b, a = M(inp["base"]), M(inp["apex"])
    rb = mp.mpf(inp["base_radius"])
    ra = mp.mpf(inp.get("apex_radius", inp["base_radius"]))
    H = norm(a - b)
    k = (a - b) / H
    helper = mp.matrix([1, 0, 0]) if abs(k[0]) < 0.9 else mp.matrix([0, 1, 0])
    e1 = unit(cross(helper, k))
    e2 = cross(k, e1)
    m = (ra - rb) / H
    ol = [dot(o - b, e) for e in (e1, e2, k)]
    dl = [dot(d, e) for e in (e1, e2, k)]
    # (ox + t dx)^2 + (oy + t dy)^2 - (rb + m (oz + t dz))^2 = 0
    A = dl[0] ** 2 + dl[1] ** 2 - (m * dl[2]) ** 2
    B = 2 * (ol[0] * dl[0] + ol[1] * dl[1] - m * dl[2] * (rb + m * ol[2]))
    C = ol[0] ** 2 + ol[1] ** 2 - (rb + m * ol[2]) ** 2
    roots = []
    if A == 0:
        if B != 0:
            roots = [-C / B]
    else:
        D = B * B - 4 * A * C
        if D >= 0:
            roots = sorted([(-B - mp.sqrt(D)) / (2 * A), (-B + mp.sqrt(D)) / (2 * A)])
    for t in roots:
        z = ol[2] + t * dl[2]
        if t >= 0 and 0 <= z <= H:
            x, y = ol[0] + t * dl[0], ol[1] + t * dl[1]
            rho = mp.sqrt(x * x + y * y)
            n = (x / rho) * e1 + (y / rho) * e2 - m * k
            return {"t": F(t), "hit": True, "point": FV(o + t * d), "normal": FV(unit(n))}
    return {"t": None, "hit": False, "point": None, "normal": None}


for fid in ("intersect-cylinder", "intersect-cone"):
    for k in range(12):
        b, a = rv(), rv()
        rb = float(rng.uniform(0.3, 2))
        ra = rb if fid == "intersect-cylinder" else float(rng.uniform(0, 2))
        s = float(rng.uniform(0, 1))
        aim = [b[i] + s * (a[i] - b[i]) + float(rng.uniform(-1.5, 1.5)) for i in range(3)]
        o = rv(s=12)
        d = [aim[i] - o[i] for i in range(3)]
        inp = {"origin": o, "dir": d, "base": b, "base_radius": rb, "apex": a}
        if fid == "intersect-cone" or k % 2:
            inp["apex_radius"] = ra
        add(fid, inp, cone(inp), MP + "; quadratic in the cone's own orthonormal frame")
add("intersect-cylinder", {"origin": [-5, 0, 1], "dir": [1, 0, 0], "base": [0, 0, 0], "base_radius": 1, "apex": [0, 0, 2]},
    {"t": 4.0, "hit": True, "point": [-1, 0, 1], "normal": [-1, 0, 0]}, "by hand: from outside")
add("intersect-cylinder", {"origin": [0, 0, 1], "dir": [1, 0, 0], "base": [0, 0, 0], "base_radius": 1, "apex": [0, 0, 2]},
    {"t": 1.0, "hit": True, "point": [1, 0, 1], "normal": [1, 0, 0]}, "by hand: from inside (open surface)")
add("intersect-cylinder", {"origin": [-5, 0, 3], "dir": [1, 0, 0], "base": [0, 0, 0], "base_radius": 1, "apex": [0, 0, 2]},
    {"t": None, "hit": False}, "by hand: past the apex end")
add("intersect-cone", {"origin": [-5, 0, 0.5], "dir": [1, 0, 0], "base": [0, 0, 0], "base_radius": 1, "apex": [0, 0, 1],
                       "apex_radius": 0}, {"t": 4.5, "hit": True, "point": [-0.5, 0, 0.5],
                                            "normal": FV(unit(mp.matrix([-1, 0, 1])))}, "by hand: slope -1")
add("intersect-cone", {"origin": [-5, 0, 1.5], "dir": [1, 0, 0], "base": [0, 0, 0], "base_radius": 1, "apex": [0, 0, 1],
                       "apex_radius": 0}, {"t": None, "hit": False}, "by hand: the mirrored nappe past the tip is not part of it")
err("intersect-cone", {"origin": [0, 0, 0], "dir": [1, 0, 0], "base": [1, 1, 1], "base_radius": 1, "apex": [1, 1, 1],
                       "apex_radius": 0.5}, "base = apex")
err("intersect-cylinder", {"origin": [0, 0, 0], "dir": [1, 0, 0], "base": [0, 0, 0], "base_radius": 1, "apex": [0, 0, 1],
                           "apex_radius": 2}, "a cylinder with two radii")
err("intersect-cone", {"origin": [0, 0, 0], "dir": [1, 0, 0], "base": [0, 0, 0], "base_radius": -1, "apex": [0, 0, 1],
                       "apex_radius": -0.5}, "negative radii (NFF inside-only is the scene's business)")


# ---------------------------------------------------------------- 3.6.2 phong, reflect
def phong(inp):
    n, l, v = unit(M(inp["n"])), unit(M(inp["l"])), unit(M(inp["v"]))
    IL = M(inp.get("light", [1, 1, 1]))
    ka, kd, ks = M(inp["ka"]), M(inp["kd"]), M(inp["ks"])
    nl = dot(n, l)
    rl = 2 * n * nl - l  # erratum 3.6.2
    rv_ = dot(rl, v)
    dif = max(nl, 0)
    spec = rv_ ** mp.mpf(inp["shininess"]) if (nl > 0 and rv_ > 0) else 0
    amb = [ka[i] * IL[i] for i in range(3)]
    di = [kd[i] * IL[i] * dif for i in range(3)]
    sp = [ks[i] * IL[i] * spec for i in range(3)]
    return {"ambient": FV(amb), "diffuse": FV(di), "specular": FV(sp), "total": FV([amb[i] + di[i] + sp[i] for i in range(3)]),
            "r_l": FV(rl), "n_dot_l": F(nl), "r_dot_v": F(rv_)}


for k in range(12):
    n = rv()
    nn = np.array(n) / np.linalg.norm(n)
    l = rv()
    if k < 9 and np.dot(l, nn) < 0:
        l = list(np.array(l) - 2 * np.dot(l, nn) * nn)  # mostly lit
    r_ = 2 * np.dot(nn, l) / np.dot(l, l) ** 0.5 * nn - np.array(l) / np.linalg.norm(l)
    v = list(r_ + rng.uniform(-0.4, 0.4, 3)) if k % 3 else rv()
    inp = {"n": n, "l": [float(x) for x in l], "v": [float(x) for x in v], "ka": list(rng.uniform(0, 0.3, 3)),
           "kd": list(rng.uniform(0, 1, 3)), "ks": list(rng.uniform(0, 1, 3)), "shininess": float(rng.uniform(1, 60))}
    if k % 2:
        inp["light"] = list(rng.uniform(0, 3, 3))
    inp = json.loads(json.dumps(inp))
    add("phong", inp, phong(inp), MP + "; R_L = 2N<N,L> - L (erratum 3.6.2), negative products count as 0")
s2 = 0.5 ** 0.5
add("phong", {"n": [0, 0, 1], "l": [0, 1, 1], "v": [0, 0, 1], "ka": [0.1, 0.2, 0.3], "kd": [0.5, 0.6, 0.7],
              "ks": [0.8, 0.4, 0.2], "shininess": 10, "light": [1, 0.5, 2]},
    {"ambient": [0.1, 0.1, 0.6], "diffuse": [0.5 * s2, 0.3 * s2, 1.4 * s2], "specular": [0.025, 0.00625, 0.0125],
     "r_l": [0, -s2, s2]}, "by hand: <N,L> = <R_L,V> = 1/sqrt2, (1/sqrt2)^10 = 1/32")
add("phong", {"n": [0, 0, 1], "l": [0, 1, -1], "v": [0, -1, -1], "ka": [0.1, 0.2, 0.3], "kd": [0.5, 0.6, 0.7],
              "ks": [0.8, 0.4, 0.2], "shininess": 10},
    {"ambient": [0.1, 0.2, 0.3], "diffuse": [0, 0, 0], "specular": [0, 0, 0], "total": [0.1, 0.2, 0.3]},
    "by hand: light below the surface, only ambient")
err("phong", {"n": [0, 0, 0], "l": [0, 1, 1], "v": [0, 0, 1], "ka": [0, 0, 0], "kd": [1, 1, 1], "ks": [1, 1, 1],
              "shininess": 10}, "zero normal")

for k in range(6):
    n, l = rv(), rv()
    nn = unit(M(n))
    add("reflect", {"n": n, "l": l}, {"r": FV(2 * nn * dot(nn, M(l)) - M(l))}, MP + "; R = 2N<N,L> - L (erratum 3.6.2)")
    add("reflect", {"n": n, "dir": l}, {"r": FV(M(l) - 2 * dot(M(l), nn) * nn)}, MP + "; D - 2<D,N>N (3.8)")
add("reflect", {"n": [0, 0, 1], "l": [1, 0, 1]}, {"r": [-1, 0, 1]}, "by hand")
err("reflect", {"n": [0, 0, 1], "l": [1, 0, 1], "dir": [1, 0, 1]}, "both l and dir")


# ---------------------------------------------------------------- 3.6.3 vertex-normal, interpolate-normal
for k in range(6):
    v0 = rv()
    faces = []
    s = mp.matrix([0, 0, 0])
    for f in range(int(rng.integers(1, 7))):
        b, c = rv(), rv()
        faces.append([v0, b, c])
        s += cross(M(b) - M(v0), M(c) - M(v0))
    add("vertex-normal", {"faces": faces}, {"n": FV(unit(s))}, MP + "; normalise(sum of (b-a) x (c-a)), area-weighted")
add("vertex-normal", {"faces": [[[0, 0, 0], [2, 0, 0], [0, 2, 0]], [[0, 0, 0], [1, 0, 0], [0, 0, 1]]]},
    {"n": FV(unit(mp.matrix([0, -1, 4])))}, "by hand: areas 2 and 0.5 weigh +z and -y; the plain mean would be (0,-1,1)/sqrt2")
err("vertex-normal", {"faces": [[[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 0, 0], [0, 1, 0], [1, 0, 0]]]}, "normals cancel")
err("vertex-normal", {"faces": [[0, 0, 0], [1, 0, 0], [0, 1, 0]]}, "a flat list of corners is not a list of triangles")

for k in range(6):
    ns = [runit() for _ in range(3)]
    a, b = rng.uniform(0, 1, 2)
    ls = [float(x) for x in (1 - a - b, a, b)]
    s = sum((mp.mpf(ls[i]) * M(ns[i]) for i in range(3)), mp.matrix([0, 0, 0]))
    add("interpolate-normal", {"n1": ns[0], "n2": ns[1], "n3": ns[2], "l1": ls[0], "l2": ls[1], "l3": ls[2]},
        {"n": FV(unit(s))}, MP + "; normalise(l1 n1 + l2 n2 + l3 n3)")


# ---------------------------------------------------------------- 3.7 lights
for k in range(6):
    I, pos, p = list(rng.uniform(0, 10, 3)), rv(), rv()
    I = [float(x) for x in I]
    to = M(pos) - M(p)
    dd = norm(to)
    fall = "none" if k % 3 == 2 else "inverse-square"
    inp = {"intensity": I, "light_pos": pos, "point": p}
    if k % 3:
        inp["falloff"] = fall
    add("light-point", inp, {"i": FV([x / dd ** 2 if fall == "inverse-square" else x for x in M(I)]), "l": FV(to / dd),
                             "distance": F(dd)}, MP + "; I/d^2 (none: I)")
for k in range(3):
    E, d = [float(x) for x in rng.uniform(0, 3, 3)], rv()
    add("light-directional", {"irradiance": E, "direction": d}, {"i": E, "l": FV(-unit(M(d))), "distance": None},
        MP + "; l = -direction normalised")
err("light-directional", {"irradiance": [1, 1, 1], "direction": [0, 0, 0]}, "zero direction")
for k in range(8):
    I, pos = [float(x) for x in rng.uniform(0, 10, 3)], rv()
    axis = rv()
    p = list(np.array(pos) + 3 * np.array(axis) / np.linalg.norm(axis) + rng.uniform(-2, 2, 3))
    p = [float(x) for x in p]
    ex, cut = float(rng.uniform(0, 20)), float(rng.uniform(5, 89))
    to = M(pos) - M(p)
    dd = norm(to)
    th = mp.acos(dot(unit(M(axis)), -to / dd))
    w = mp.cos(th) ** ex if deg(th) <= cut else 0
    if abs(deg(th) - cut) < 1e-6:
        continue
    add("light-spot", {"intensity": I, "light_pos": pos, "axis": axis, "exponent": ex, "cutoff_deg": cut, "point": p},
        {"i": FV([x * w / dd ** 2 for x in M(I)]), "l": FV(to / dd), "distance": F(dd), "theta_deg": F(deg(th))},
        MP + "; I cos^n(theta)/d^2 inside the cutoff, 0 outside")
err("light-spot", {"intensity": [1, 1, 1], "light_pos": [0, 0, 0], "axis": [0, 0, 0], "exponent": 1, "cutoff_deg": 30,
                   "point": [0, 0, -1]}, "zero axis")


# ---------------------------------------------------------------- 3.8.1 optics
C0 = 299792458
for cm in (C0, 225000000.0, 199861638.67, 124000000.0):
    add("ior", {"c_medium": cm}, {"eta": F(mp.mpf(C0) / mp.mpf(cm))}, "eta = c0/c, c0 = 299792458 m/s exact")


def snell(ei, et, th_deg):
    ei, et = mp.mpf(ei), mp.mpf(et)
    s = ei / et * mp.sin(rad(th_deg))
    crit = F(deg(mp.asin(et / ei))) if ei > et else None
    if s > 1:
        return {"theta_t_deg": None, "tir": True, "critical_deg": crit}
    return {"theta_t_deg": F(deg(mp.asin(s))), "tir": False, "critical_deg": crit}


for k in range(12):
    ei, et = float(rng.uniform(1, 2.5)), float(rng.uniform(1, 2.5))
    th = float(rng.uniform(0, 89))
    ex = snell(ei, et, th)
    if ex["critical_deg"] is not None and abs(th - ex["critical_deg"]) < 1e-3:
        continue
    add("snell", {"eta_i": ei, "eta_t": et, "theta_i_deg": th}, ex, MP + "; eta_i sin(theta_i) = eta_t sin(theta_t)")
crit = F(deg(mp.asin(mp.mpf(1) / mp.mpf(1.5))))
add("snell", {"eta_i": 1.5, "eta_t": 1.0, "theta_i_deg": crit}, {"theta_t_deg": 90.0, "tir": False, "critical_deg": crit},
    "at the critical angle (41.8103149 deg): theta_t = 90, no TIR (pinned); theta_t has sqrt sensitivity to the "
    "rounding of the input, hence rel 1e-7", rel=1e-7)
add("snell", {"eta_i": 1.5, "eta_t": 1.0, "theta_i_deg": 42.0}, snell(1.5, 1.0, 42.0), "beyond the critical angle: TIR")
add("snell", {"eta_i": 1.0, "eta_t": 1.5, "theta_i_deg": 0.0}, {"theta_t_deg": 0.0, "tir": False, "critical_deg": None},
    "normal incidence")
err("snell", {"eta_i": 0, "eta_t": 1.5, "theta_i_deg": 10}, "eta 0")


def refract(inp):
    i, n = unit(M(inp["i"])), unit(M(inp["n"]))
    eta = mp.mpf(inp["eta_i"]) / mp.mpf(inp["eta_t"])
    c = dot(i, n)
    k = 1 - eta ** 2 * (1 - c ** 2)
    if k < 0:
        return {"t": None, "tir": True, "cos_i": F(c)}
    return {"t": FV(-eta * i + (eta * c - mp.sqrt(k)) * n), "tir": False, "cos_i": F(c)}


for k in range(12):
    n, i = rv(), rv()
    if np.dot(i, n) < 0:
        i = [-x for x in i]
    inp = {"i": i, "n": n, "eta_i": float(rng.uniform(1, 2.5)), "eta_t": float(rng.uniform(1, 2.5))}
    ex = refract(inp)
    eta = inp["eta_i"] / inp["eta_t"]
    if abs(1 - eta ** 2 * (1 - ex["cos_i"] ** 2)) < 1e-4:
        continue
    add("refract", inp, ex, MP + "; the script's T formula (3.8.1)")
add("refract", {"i": [0, 0.5, 0.75 ** 0.5], "n": [0, 0, 1], "eta_i": 1, "eta_t": 1.5},
    refract({"i": [0, 0.5, 0.75 ** 0.5], "n": [0, 0, 1], "eta_i": 1, "eta_t": 1.5}), "30 deg into glass: sin_t = 1/3")
add("refract", {"i": [0, 0.75 ** 0.5, 0.5], "n": [0, 0, 1], "eta_i": 1.5, "eta_t": 1},
    {"t": None, "tir": True, "cos_i": 0.5}, "60 deg from glass: TIR")
err("refract", {"i": [0, 0, -1], "n": [0, 0, 1], "eta_i": 1, "eta_t": 1.5}, "i on the other side of n")


def fresnel(ei, et, ci, variant="exact"):
    ei, et, ci = mp.mpf(ei), mp.mpf(et), mp.mpf(ci)
    if ei == et:
        return {"r": 0.0, "t": 1.0, "rs": 0.0 if variant == "exact" else None, "rp": 0.0 if variant == "exact" else None, "tir": False}
    st2 = (ei / et) ** 2 * (1 - ci ** 2)
    if st2 > 1:
        one = 1.0 if variant == "exact" else None
        return {"r": 1.0, "t": 0.0, "rs": one, "rp": one, "tir": True}
    ct = mp.sqrt(1 - st2)
    if variant == "exact":
        rs = ((ei * ci - et * ct) / (ei * ci + et * ct)) ** 2
        rp = ((et * ci - ei * ct) / (et * ci + ei * ct)) ** 2
        r = (rs + rp) / 2
        return {"r": F(r), "t": F(1 - r), "rs": F(rs), "rp": F(rp), "tir": False}
    r0 = ((ei - et) / (ei + et)) ** 2
    x = 1 - (ct if ei > et else ci)
    r = r0 + (1 - r0) * x ** 5
    return {"r": F(r), "t": F(1 - r), "rs": None, "rp": None, "tir": False}


for variant in ("exact", "schlick"):
    for k in range(10):
        ei, et, ci = float(rng.uniform(1, 2.5)), float(rng.uniform(1, 2.5)), float(rng.uniform(0, 1))
        st2 = (ei / et) ** 2 * (1 - ci * ci)
        if abs(st2 - 1) < 1e-4:
            continue
        inp = {"eta_i": ei, "eta_t": et, "cos_i": ci}
        if variant == "schlick":
            inp["variant"] = variant
        add("fresnel", inp, fresnel(ei, et, ci, variant), MP + "; Fresnel equations (unpolarised mean)" if variant == "exact"
            else MP + "; Schlick with the cosine on the thinner side")
    v = {} if variant == "exact" else {"variant": variant}
    add("fresnel", dict({"eta_i": 1, "eta_t": 1.5, "cos_i": 1}, **v), {"r": 0.04, "t": 0.96, "tir": False},
        "normal incidence: ((1.5-1)/(1.5+1))^2 = 0.04")
    add("fresnel", dict({"eta_i": 1.5, "eta_t": 1, "cos_i": 0.5}, **v), {"r": 1.0, "t": 0.0, "tir": True},
        "60 deg from glass: total internal reflection")
    add("fresnel", dict({"eta_i": 1, "eta_t": 1.5, "cos_i": 0}, **v), {"r": 1.0, "t": 0.0, "tir": False}, "grazing")
cc = float(mp.sqrt(1 - (mp.mpf(1) / mp.mpf(1.5)) ** 2))
add("fresnel", {"eta_i": 1.5, "eta_t": 1, "cos_i": cc}, {"r": 1.0}, "at the critical angle r = 1; r rises like "
    "1 - O(sqrt(angle)) below it, so the rounding of cos_i allows rel 1e-6", rel=1e-6)
add("fresnel", {"eta_i": 1, "eta_t": 1.5, "cos_i": F(mp.cos(mp.atan(mp.mpf(1.5))))}, {"rp": 0.0},
    "Brewster's angle tan = eta_t/eta_i: rp = 0", abs=1e-30)
err("fresnel", {"eta_i": 1, "eta_t": 1.5, "cos_i": 1.5}, "cos_i > 1")

for lam, a, b in [(589.3, 1.5046, 0.0042), (486.1, 1.5046, 0.0042), (656.3, 1.5046, 0.0042), (400, 1.3, 0.003)]:
    add("dispersion", {"lambda_nm": lam, "a": a, "b": b},
        {"eta": F(mp.mpf(a) + mp.mpf(b) / (mp.mpf(lam) / 1000) ** 2)}, "Cauchy, lambda in micrometres")


# ---------------------------------------------------------------- 3.10 thin-lens
for k in range(8):
    while True:
        lu, lv = [float(x) for x in rng.uniform(-1, 1, 2)]
        if lu * lu + lv * lv <= 1:
            break
    pd = [float(rng.uniform(-1, 1)), float(rng.uniform(-1, 1)), float(-rng.uniform(0.5, 2))]
    ap, fd = float(rng.uniform(0, 0.5)), float(rng.uniform(0.5, 20))
    P = M(pd)
    focus = P * (mp.mpf(fd) / -P[2])
    lens = mp.matrix([ap * mp.mpf(lu), ap * mp.mpf(lv), 0])
    add("thin-lens", {"lens_u": lu, "lens_v": lv, "aperture_radius": ap, "focal_distance": fd, "pixel_direction": pd},
        {"origin": FV(lens), "direction": FV(unit(focus - lens))}, MP + "; the ray from the lens point to the focal-plane point")
err("thin-lens", {"lens_u": 0, "lens_v": 0, "aperture_radius": 0.1, "focal_distance": 1, "pixel_direction": [0, 0, 1]},
    "pixel direction away from the scene")
err("thin-lens", {"lens_u": 1, "lens_v": 1, "aperture_radius": 0.1, "focal_distance": 1, "pixel_direction": [0, 0, -1]},
    "lens point outside the unit disk")

for c in cases:
    sys.stdout.write(json.dumps(c) + "\n")
sys.stderr.write(f"{len(cases)} cases\n")
