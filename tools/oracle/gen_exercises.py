#!/usr/bin/env python3
"""Writes docs/exercises.jsonl: an example solution sheet for `refray formula --batch FILE --check`.

Every "expect" is computed here, independently of refray: with numpy (vectors, matrices,
rotations, ray/sphere, Fresnel, Snell, refraction) and Python's colorsys (HSV), or by hand where
the value is exact. Angles are in degrees in every formula (inputs and outputs named *_deg).
Inputs show both spellings: JSON arrays and the command-line form as a string ("1,2;3,4").
Run: python3 tools/oracle/gen_exercises.py > docs/exercises.jsonl
"""
import colorsys
import json
import math

import numpy as np


def rot(axis, deg):
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    if axis == "x":
        return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])
    if axis == "y":
        return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def unit(v):
    v = np.asarray(v, float)
    return v / np.linalg.norm(v)


def L(x):
    return np.asarray(x, float).tolist()


cases = []


def case(id_, inputs, expect, **extra):
    c = {"id": id_, "in": inputs, "expect": expect}
    c.update(extra)
    cases.append(c)


# --- vectors (§2) ---
a, b = np.array([1, 2, 3.0]), np.array([4, 5, 6.0])
case("dot", {"a": [1, 2, 3], "b": [4, 5, 6]},
     {"dot": float(a @ b), "angle_deg": math.degrees(math.acos(a @ b / np.linalg.norm(a) / np.linalg.norm(b)))})
case("cross", {"a": "1,2,3", "b": "4,5,6"}, {"cross": L(np.cross(a, b))})
case("length", {"a": "3,4"}, {"length": 5.0, "unit": [0.6, 0.8]})
P = np.array([[0, 0], [4, 0], [0, 4.0]])
q = np.array([1, 1.0])
# q = l1 p1 + l2 p2 + l3 p3 with l1 + l2 + l3 = 1
lam = np.linalg.solve(np.vstack([P.T, np.ones(3)]), np.append(q, 1))
case("barycentric", {"p1": [0, 0], "p2": [4, 0], "p3": [0, 4], "q": [1, 1]},
     {"l1": lam[0], "l2": lam[1], "l3": lam[2], "inside": True})

# --- matrices (§4): nested arrays and the command-line form ---
M = np.array([[1, 2], [3, 4.0]])
case("inverse", {"matrix": [[1, 2], [3, 4]]}, {"inverse": L(np.linalg.inv(M)), "det": float(np.linalg.det(M))})
case("inverse", {"matrix": "2,0,0;0,4,0;0,0,8", "kind": "scale"},
     {"inverse": L(np.diag([0.5, 0.25, 0.125])), "det": 64.0})
T = np.array([[1, 0, 0, 1], [0, 1, 0, 2], [0, 0, 1, 3], [0, 0, 0, 1.0]])
case("transform-point", {"matrix": "1,0,0,1;0,1,0,2;0,0,1,3;0,0,0,1", "x": [1, 1, 1]},
     {"y": L((T @ [1, 1, 1, 1])[:3]), "w": 1.0})
case("transform-direction", {"matrix": "1,0,0,1;0,1,0,2;0,0,1,3;0,0,0,1", "x": [1, 1, 1]},
     {"y": [1.0, 1.0, 1.0], "w": 0.0})
A, bb = np.array([[1, 2], [3, 4.0]]), np.array([5, 6.0])
case("affine", {"a": "1,2;3,4", "b": "5,6", "x": [1, 1]},
     {"y": L(A @ [1, 1] + bb), "matrix_h": [[1, 2, 5], [3, 4, 6], [0, 0, 1]]})
# a singular matrix has no inverse: the sheet expects the error (numpy: det = 0, rank 1)
Sing = np.array([[1, 2], [2, 4.0]])
assert np.linalg.matrix_rank(Sing) == 1
case("inverse", {"matrix": "1,2;2,4"}, {"error": "singular"})
S = np.diag([2.0, 1, 1])
case("transform-normal", {"matrix": "2,0,0;0,1,0;0,0,1", "n": [1, 1, 0]},
     {"n": L(unit(np.linalg.inv(S).T @ [1, 1, 0])), "similarity": False})

# --- angles: degrees everywhere ---
case("rotate2", {"phi_deg": 30, "point": [1, 0]},
     {"matrix": L(rot("z", 30)[:2, :2]), "point": L(rot("z", 30)[:2, :2] @ [1, 0])})
case("rotate3", {"axis": "z", "phi_deg": 90, "point": [1, 0, 0]}, {"point": [0.0, 1.0, 0.0]})
case("euler", {"psi_deg": 30, "theta_deg": 45, "phi_deg": 60, "order": "zyx"},
     {"matrix": L(rot("z", 60) @ rot("y", 45) @ rot("x", 30))})
sin_t = math.sin(math.radians(30)) / 1.5
case("snell", {"eta_i": 1, "eta_t": 1.5, "theta_i_deg": 30},
     {"theta_t_deg": math.degrees(math.asin(sin_t)), "tir": False, "critical_deg": None})
case("snell", {"eta_i": 1.5, "eta_t": 1, "theta_i_deg": 60},
     {"theta_t_deg": None, "tir": True, "critical_deg": math.degrees(math.asin(1 / 1.5))})

# --- ray tracing (§3) ---
case("intersect-sphere", {"origin": [0, 0, 5], "dir": [0, 0, -1], "center": [0, 0, 0], "radius": 1},
     {"a": 1.0, "b": -10.0, "c": 24.0, "disc": 4.0, "t1": 4.0, "t2": 6.0, "t": 4.0, "hit": True,
      "point": [0.0, 0.0, 1.0], "normal": [0.0, 0.0, 1.0]})
case("reflect", {"n": [0, 1, 0], "dir": [1, -1, 0]}, {"r": [1.0, 1.0, 0.0]})
I, N, eta = unit([0, 1, 1]), np.array([0, 1, 0.0]), 1 / 1.5
ci = I @ N
case("refract", {"i": [0, 1, 1], "n": [0, 1, 0], "eta_i": 1, "eta_t": 1.5},
     {"t": L(-eta * I + (eta * ci - math.sqrt(1 - eta ** 2 * (1 - ci ** 2))) * N), "tir": False, "cos_i": ci})
ct = math.sqrt(1 - (1 / 1.5) ** 2 * (1 - 0.25))
rs = ((1 * 0.5 - 1.5 * ct) / (1 * 0.5 + 1.5 * ct)) ** 2
rp = ((1.5 * 0.5 - 1 * ct) / (1.5 * 0.5 + 1 * ct)) ** 2
case("fresnel", {"eta_i": 1, "eta_t": 1.5, "cos_i": 0.5},
     {"r": (rs + rp) / 2, "t": 1 - (rs + rp) / 2, "rs": rs, "rp": rp, "tir": False})
case("camera-basis", {"eye": [0, 0, 5], "target": [0, 0, 0], "up": [0, 1, 0]},
     {"u": [1.0, 0.0, 0.0], "v": [0.0, 1.0, 0.0], "w": [0.0, 0.0, 1.0]})
case("light-point", {"intensity": 100, "light_pos": [0, 10, 0], "point": [0, 0, 0]},
     {"i": [1.0, 1.0, 1.0], "l": [0.0, 1.0, 0.0], "distance": 10.0})

# --- colours (§1): a number where a colour is expected is grey ---
case("luminance", {"rgb": [1, 0.5, 0.25]}, {"y": 0.3 * 1 + 0.59 * 0.5 + 0.11 * 0.25})
h, s, v = colorsys.rgb_to_hsv(1, 0.5, 0.25)
case("rgb-to-hsv", {"rgb": "1,0.5,0.25"}, {"h_deg": h * 360, "s": s, "v": v})
case("hsv-to-rgb", {"h_deg": 200, "s": 0.5, "v": 0.8}, {"rgb": list(colorsys.hsv_to_rgb(200 / 360, 0.5, 0.8))})
enc = 1.055 * 0.5 ** (1 / 2.4) - 0.055
case("srgb-encode", {"rgb": 0.5}, {"rgb": [enc, enc, enc]})
case("xyz-to-xyy", {"xyz": [0.25, 0.5, 0.25]}, {"x": 0.25, "y": 0.5, "Y": 0.5})
case("rgb-to-cmy", {"rgb": 0.25}, {"cmy": [0.75, 0.75, 0.75]})

for c in cases:
    print(json.dumps(c, separators=(",", ":")))
