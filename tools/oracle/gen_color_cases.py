#!/usr/bin/env python3
"""Expected values for the §1 formulas, computed independently of refray's C code.

Run from the repository root:  python3 tools/oracle/gen_color_cases.py
Writes tests/data/formula_cases_color.jsonl, one case per line:
  {"id": ..., "in": {...}, "expect": {...}, "rel": 1e-9, "source": "..."}   or
  {"id": ..., "in": {...}, "error": true, "source": "..."}                   (must be refused)
tests/test_color.c runs each case through the formula registry and compares every expected field
(rel: relative tolerance; 1e-9, spectral sums 1e-6; plus an absolute floor of 1e-12).
Only for regenerating the file: the build and the tests do not run Python.

Oracles: colour-science 0.4.7 (colour.eotf_sRGB, colour.RGB_to_HSV, colour.XYZ_to_xyY,
colour.normalised_primary_matrix, its CIE tables), mpmath 1.3 (50-digit evaluation of the
closed forms of §1.1-1.3), Python's colorsys, and numpy code written here from the definitions
in FORMULAS.md (spectral sums with np.interp; chromaticity-diagram geometry with linear solves).
"""
import colorsys
import json
import math
import os
import warnings

warnings.filterwarnings("ignore")
import colour  # noqa: E402
import mpmath  # noqa: E402
import numpy as np  # noqa: E402
from colour.colorimetry.datasets import cmfs as ds  # noqa: E402

mpmath.mp.dps = 50
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CASES = []
THIRD = [1 / 3, 1 / 3]
SRGB = [[0.64, 0.33], [0.3, 0.6], [0.15, 0.06]]


def case(id_, inp, expect, source, rel=1e-9):
    CASES.append({"id": id_, "in": inp, "expect": expect, "rel": rel, "source": source})


def error(id_, inp, why):
    CASES.append({"id": id_, "in": inp, "error": True, "source": why})


def f(x):
    return float(x)


# ---- §1.1 (mpmath, 50 digits) ----
M = "mpmath 50 digits from the definition"
for lo, hi, k in [(1, 100, 0), (0.5, 250, 2), (0.01, 1, 0.001)]:
    case("dynamic-range", {"i_min": lo, "i_max": hi, "k": k},
         {"r_d": f((mpmath.mpf(hi) + k) / (mpmath.mpf(lo) + k))}, M)
error("dynamic-range", {"i_min": 0, "i_max": 1}, "I_min + k = 0")
for lo, hi, st in [(1, 100, 0.02), (0.2, 50, 0.01), (1, 1000, 0.02)]:
    steps = (mpmath.mpf(hi) - lo) / (mpmath.mpf(st) * lo)
    case("linear-steps", {"i_min": lo, "i_max": hi, "step": st},
         {"steps": f(steps), "bits": f(mpmath.ceil(mpmath.log(steps, 2)))}, M)
    e = mpmath.ceil(mpmath.log(mpmath.mpf(hi) / lo) / mpmath.log(1 + mpmath.mpf(st)))
    case("exp-steps", {"i_min": lo, "i_max": hi, "step": st},
         {"steps": f(e), "bits": f(mpmath.ceil(mpmath.log(e, 2))),
          "steps_script": f(mpmath.log10(mpmath.mpf(hi) / lo) * 120)}, M)
error("linear-steps", {"i_min": 0, "i_max": 100}, "I_min = 0")
error("exp-steps", {"i_min": 2, "i_max": 1}, "I_max < I_min")
for lo, n, st in [(1, 0, 0.02), (1, 1, 0.02), (0.5, 240, 0.02), (2, 17.5, 0.05)]:
    case("exp-level", {"i_min": lo, "n": n, "step": st},
         {"i": f(mpmath.mpf(lo) * (1 + mpmath.mpf(st)) ** n)}, M)
for n, nm, g, im in [(128, 255, 2.2, 1), (0, 255, 2.2, 1), (255, 255, 2.5, 100), (10, 1023, 1.8, 350)]:
    case("power-transfer", {"n": n, "n_max": nm, "gamma": g, "i_max": im},
         {"i": f((mpmath.mpf(n) / nm) ** mpmath.mpf(g) * im)}, M)
error("power-transfer", {"n": 300, "n_max": 255, "gamma": 2.2}, "n > N")

# ---- §1.1.2 gamma, sRGB, quantisation ----
for rgb, g in [([0.5, 0.25, 1.0], 2.2), ([0.0, 0.001, 0.9], 2.4), ([0.18, 0.5, 0.75], 1.8)]:
    case("gamma-encode", {"rgb": rgb, "gamma": g},
         {"rgb": [f(mpmath.mpf(v) ** (1 / mpmath.mpf(g))) if v > 0 else 0.0 for v in rgb]}, M)
    case("gamma-decode", {"rgb": rgb, "gamma": g},
         {"rgb": [f(mpmath.mpf(v) ** mpmath.mpf(g)) for v in rgb]}, M)
error("gamma-encode", {"rgb": [0.5, 0.5, 0.5], "gamma": 0}, "gamma = 0")
for rgb in [[0.0, 0.002, 0.0031308], [0.01, 0.18, 0.5], [0.75, 0.9, 1.0]]:
    case("srgb-encode", {"rgb": rgb}, {"rgb": [f(v) for v in colour.models.eotf_inverse_sRGB(np.array(rgb))]},
         "colour-science colour.models.eotf_inverse_sRGB")
for rgb in [[0.0, 0.02, 0.04], [0.05, 0.5, 0.735], [0.9, 0.99, 1.0]]:
    case("srgb-decode", {"rgb": rgb}, {"rgb": [f(v) for v in colour.models.eotf_sRGB(np.array(rgb))]},
         "colour-science colour.models.eotf_sRGB")
# At the switch itself colour-science uses 12.92 * 0.0031308 = 0.040449936; the pinned convention
# (IEC text) is v <= 0.04045, so the boundary case comes from the IEC formula (mpmath).
def srgb_dec_iec(v):
    v = mpmath.mpf(v)
    return f(v / mpmath.mpf("12.92") if v <= mpmath.mpf("0.04045") else ((v + mpmath.mpf("0.055")) / mpmath.mpf("1.055")) ** mpmath.mpf("2.4"))
case("srgb-decode", {"rgb": [0.04045, 0.0404500001, 0.04044]}, {"rgb": [srgb_dec_iec(v) for v in [0.04045, 0.0404500001, 0.04044]]},
     "mpmath, IEC 61966-2-1 text (switch at v <= 0.04045)")
for v, b in [(0.5, 8), (0.2, 8), (1.5, 8), (-0.1, 8), (0.123456, 16), (0.5, 1), (0.7, 10)]:
    mx = 2 ** b - 1
    code = min(max(math.floor(v * mx + 0.5), 0), mx)
    case("quantize", {"value": v, "bits": b}, {"code": float(code)}, "python round half up, clamped")
error("quantize", {"value": 0.5, "bits": 0}, "bits = 0")

# ---- §1.2 alpha over (numpy from the Porter-Duff definition) ----
for ca, aa, cb, ab in [([1, 0, 0], 0.5, [0, 0, 1], 1.0), ([0.2, 0.4, 0.6], 0.25, [0.9, 0.8, 0.1], 0.5),
                       ([0.3, 0.3, 0.3], 0.0, [0.1, 0.2, 0.3], 0.0), ([0.5, 0.6, 0.7], 1.0, [0, 0, 0], 0.3)]:
    ca_, cb_ = np.array(ca, float), np.array(cb, float)
    a = aa + ab * (1 - aa)
    rgb = (ca_ * aa + cb_ * ab * (1 - aa)) / a if a > 0 else np.zeros(3)
    case("alpha-over", {"rgb_a": ca, "alpha_a": aa, "rgb_b": cb, "alpha_b": ab},
         {"rgb": [f(v) for v in rgb], "alpha": a}, "numpy, Porter & Duff 1984 'over' (straight)")
    pa, pb = ca_ * aa, cb_ * ab  # premultiplied inputs
    case("alpha-over", {"rgb_a": list(map(float, pa)), "alpha_a": aa, "rgb_b": list(map(float, pb)),
                        "alpha_b": ab, "premultiplied": True},
         {"rgb": [f(v) for v in pa + pb * (1 - aa)], "alpha": a}, "numpy, Porter & Duff 'over' (premultiplied)")
error("alpha-over", {"rgb_a": [1, 0, 0], "alpha_a": 1.5, "rgb_b": [0, 0, 0], "alpha_b": 1}, "alpha > 1")

# ---- §1.3 ----
for lam in [380, 555, 700, 632.8]:
    case("frequency", {"lambda_nm": lam},
         {"nu_hz": f(mpmath.mpf(colour.constants.CONSTANT_LIGHT_SPEED) / (mpmath.mpf(lam) * mpmath.mpf("1e-9")))},
         "mpmath with colour.constants.CONSTANT_LIGHT_SPEED")
error("frequency", {"lambda_nm": 0}, "lambda = 0")

# ---- spectra: numpy sums over colour-science's tables ----
def table(data, step_to_1nm=False):
    wl = np.array(sorted(data.keys()), float)
    v = np.array([data[w] for w in sorted(data.keys())], float)
    if step_to_1nm:
        grid = np.arange(wl[0], wl[-1] + 1)
        v = np.stack([np.interp(grid, wl, v[:, i]) for i in range(3)], axis=1)
        wl = grid
    return wl, v


XYZ_T = table(ds.DATA_CMFS_STANDARD_OBSERVER["CIE 1931 2 Degree Standard Observer"])
LMS_T = table(ds.DATA_CMFS_LMS["Stockman & Sharpe 2 Degree Cone Fundamentals"])
RGB_T = table(ds.DATA_CMFS_RGB["Wright & Guild 1931 2 Degree RGB CMFs"], True)


def spectral_sum(tab, lam, power):
    wl, v = tab
    lam, power = np.asarray(lam, float), np.asarray(power, float)
    p = np.interp(wl, lam, power, left=0.0, right=0.0)
    return [f(np.sum(v[:, i] * p)) for i in range(3)]


SPECTRA = [
    ([555], [1.0]),
    ([400, 500, 600, 700], [0.2, 1.0, 0.5, 0.1]),
    (list(range(380, 781, 10)), [1.0] * 41),
    ([450.5, 451.7, 520.25, 610.0, 640.3], [0.3, 2.0, 1.0, 0.7, 0.0]),
    ([360, 830], [1.0, 1.0]),
]
SRC = "numpy sums (np.interp of the spectrum onto the 1 nm grid) over colour-science %s"
for lam, pw in SPECTRA:
    x = spectral_sum(XYZ_T, lam, pw)
    case("spectrum-to-xyz", {"lambda_nm": lam, "power": pw}, {"x": x[0], "y": x[1], "z": x[2]},
         SRC % "CIE 1931 2 Degree Standard Observer", 1e-6)
    r = spectral_sum(RGB_T, lam, pw)
    case("spectrum-to-rgb", {"lambda_nm": lam, "power": pw}, {"r": r[0], "g": r[1], "b": r[2]},
         SRC % "Wright & Guild 1931 RGB CMFs (5 nm, np.interp to 1 nm)", 1e-6)
    l = spectral_sum(LMS_T, lam, pw)
    case("cone-response", {"lambda_nm": lam, "power": pw}, {"l": l[0], "m": l[1], "s": l[2]},
         SRC % "Stockman & Sharpe 2 Degree Cone Fundamentals (CIE 2006)", 1e-6)
error("spectrum-to-xyz", {"lambda_nm": [500, 400], "power": [1, 1]}, "wavelengths not increasing")
error("spectrum-to-xyz", {"lambda_nm": [400, 500], "power": [1]}, "lengths differ")

# The worked metamerism example: p1 = 1 on 400..700 nm; p2 = p1 + s B with B in the null space of
# the six functions (x̄ȳz̄ and l̄m̄s̄) within the span of 7 sine bumps (numpy SVD null vector).
grid = np.arange(400, 701)
bumps = np.stack([np.sin(k * np.pi * (grid - 400) / 300) for k in range(1, 8)])
A = np.array([[spectral_sum(t, grid, b)[i] for b in bumps] for t in (XYZ_T, LMS_T) for i in range(3)])
null = np.linalg.svd(A)[2][-1]
B = null @ bumps
p1 = np.ones_like(grid, float)
s = 0.9 * np.min(p1[B < 0] / -B[B < 0])
p2 = p1 + s * B
for name, p in (("p1 (flat)", p1), ("p2 (metamer)", p2)):
    inp = {"lambda_nm": [int(v) for v in grid], "power": [f(v) for v in p]}
    x = spectral_sum(XYZ_T, grid, p)
    case("spectrum-to-xyz", inp, {"x": x[0], "y": x[1], "z": x[2]}, "metamer example " + name + "; " +
         SRC % "CIE 1931", 1e-6)
    l = spectral_sum(LMS_T, grid, p)
    case("cone-response", inp, {"l": l[0], "m": l[1], "s": l[2]}, "metamer example " + name + "; " +
         SRC % "CIE 2006 LMS", 1e-6)

# ---- §1.4 colour models ----
for rgb in [[1, 1, 1], [0.2, 0.5, 0.9], [0.25, 0.0, 0.75]]:
    case("luminance", {"rgb": rgb}, {"y": f(mpmath.mpf("0.3") * rgb[0] + mpmath.mpf("0.59") * rgb[1]
                                            + mpmath.mpf("0.11") * rgb[2])}, M + " (0.3, 0.59, 0.11)")
    case("rgb-to-cmy", {"rgb": rgb}, {"cmy": [1.0 - v for v in rgb]}, "definition 1 - x")
    case("cmy-to-rgb", {"cmy": rgb}, {"rgb": [1.0 - v for v in rgb]}, "definition 1 - x")
for cmy in [[0.2, 0.5, 0.9], [0.6, 0.6, 0.6], [1, 1, 1], [0.0, 0.3, 0.1]]:
    k = min(cmy)
    case("cmy-to-cmyk", {"cmy": cmy}, {"cmyk": [v - k for v in cmy] + [k]}, "definition (script)")
    norm = [0.0, 0.0, 0.0, 1.0] if k == 1 else [(v - k) / (1 - k) for v in cmy] + [k]
    case("cmy-to-cmyk", {"cmy": cmy, "variant": "normalized"}, {"cmyk": norm}, "definition (normalised)")
    case("cmyk-to-cmy", {"cmyk": [v - k for v in cmy] + [k]}, {"cmy": cmy}, "round trip of the script form")
    case("cmyk-to-cmy", {"cmyk": norm, "variant": "normalized"},
         {"cmy": [v * (1 - norm[3]) + norm[3] for v in norm[:3]]}, "definition C = C'(1-K) + K")
error("cmy-to-cmyk", {"cmy": [0.1, 0.2, 0.3], "variant": "fancy"}, "bad variant")
error("cmyk-to-cmy", {"cmyk": [0.1, 0.2, 0.3]}, "3 components for cmyk")
for rgb in [[1, 0, 0], [0.2, 0.5, 0.9], [0.9, 0.2, 0.5], [0.5, 0.5, 0.5], [0, 0, 0], [0.3, 0.8, 0.1], [1, 1, 0]]:
    h, sv, v = colour.RGB_to_HSV(np.array(rgb, float))
    hc, sc, vc = colorsys.rgb_to_hsv(*rgb)
    assert abs(h - hc) < 1e-12 and abs(sv - sc) < 1e-12
    case("rgb-to-hsv", {"rgb": rgb}, {"h_deg": f(h * 360), "s": f(sv), "v": f(v)},
         "colour-science colour.RGB_to_HSV (agrees with colorsys), H x 360")
for h, sv, v in [(0, 1, 1), (200, 0.5, 0.8), (330, 0.25, 0.6), (420, 1, 0.5), (-60, 1, 1), (90, 0, 0.4)]:
    rgb = colorsys.hsv_to_rgb((h % 360) / 360, sv, v)
    case("hsv-to-rgb", {"h_deg": h, "s": sv, "v": v}, {"rgb": [f(c) for c in rgb]},
         "python colorsys.hsv_to_rgb, H mod 360")

# ---- §1.4.6 RGB <-> XYZ ----
SCRIPT = np.array([[0.49, 0.31, 0.20], [0.18, 0.81, 0.01], [0.00, 0.01, 0.99]])
CIE = np.array([[0.49, 0.31, 0.20], [0.17697, 0.81240, 0.01063], [0.00, 0.01, 0.99]]) / 0.17697
SRGB_M = colour.normalised_primary_matrix(np.array(SRGB), np.array([0.3127, 0.3290]))
for name, m, src in (("script", SCRIPT, "the script's M"), ("cie1931", CIE, "CIE 1931 / 0.17697"),
                     ("srgb", SRGB_M, "colour.normalised_primary_matrix(sRGB primaries, D65 0.3127,0.3290)")):
    for rgb in [[1, 1, 1], [0.2, 0.5, 0.9], [1, 0, 0]]:
        case("rgb-to-xyz", {"rgb": rgb, "matrix": name},
             {"xyz": [f(v) for v in m @ np.array(rgb, float)], "matrix": m.tolist()}, "numpy, " + src)
        mi = np.linalg.inv(m)
        case("xyz-to-rgb", {"xyz": rgb, "matrix": name},
             {"rgb": [f(v) for v in mi @ np.array(rgb, float)], "matrix": mi.tolist()},
             "numpy.linalg.inv, " + src)
error("rgb-to-xyz", {"rgb": [1, 1, 1], "matrix": "adobe"}, "bad matrix name")

# ---- §1.4.7 xyY ----
for xyz in [[0.95047, 1.0, 1.08883], [0.2, 0.1, 0.05], [0.0, 0.5, 0.0]]:
    r = colour.XYZ_to_xyY(np.array(xyz))
    case("xyz-to-xyy", {"xyz": xyz}, {"x": f(r[0]), "y": f(r[1]), "Y": f(r[2])}, "colour.XYZ_to_xyY")
case("xyz-to-xyy", {"xyz": [0, 0, 0]}, {"x": 1 / 3, "y": 1 / 3, "Y": 0.0}, "pinned convention: black")
error("xyz-to-xyy", {"xyz": [1, -1, 0]}, "X+Y+Z = 0, not black")
for xyy in [[0.3127, 0.329, 1.0], [0.64, 0.33, 0.2126], [0.2, 0.7, 0.5]]:
    r = colour.xyY_to_XYZ(np.array(xyy))
    case("xyy-to-xyz", {"x": xyy[0], "y": xyy[1], "Y": xyy[2]}, {"xyz": [f(v) for v in r]}, "colour.xyY_to_XYZ")
case("xyy-to-xyz", {"x": 0.3, "y": 0, "Y": 0}, {"xyz": [0.0, 0.0, 0.0]}, "pinned: y = 0, Y = 0 is black")
error("xyy-to-xyz", {"x": 0.3, "y": 0, "Y": 1}, "y = 0 with Y != 0")

# ---- §1.5 chromaticity diagram (numpy geometry written from the definitions) ----
def locus(lam):
    v = np.array([np.interp(lam, XYZ_T[0], XYZ_T[1][:, i]) for i in range(3)])
    return v[:2] / v.sum()


for lam in [360, 450, 505.5, 520, 555, 600, 700.25, 830]:
    x, y = locus(lam)
    if lam == int(lam):
        ref = colour.XYZ_to_xy(colour.wavelength_to_XYZ(lam, colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]))
        assert np.allclose(ref, [x, y], rtol=1e-12)
    case("locus", {"lambda_nm": lam}, {"x": f(x), "y": f(y)},
         "numpy interp of colour-science CIE 1931 x̄ȳz̄, normalised (integers agree with colour.wavelength_to_XYZ)")
error("locus", {"lambda_nm": 355}, "below 360 nm")

POLY = np.array([locus(l) for l in range(360, 831)])


def first_crossing(w, d):
    """Smallest t > 0 where w + t d meets the locus polyline or the purple line (830 -> 360 nm)."""
    a = np.vstack([POLY, POLY[:1]])
    best = (np.inf, None, False)
    for i in range(len(a) - 1):
        e = a[i + 1] - a[i]
        mat = np.array([[d[0], -e[0]], [d[1], -e[1]]])
        if abs(np.linalg.det(mat)) < 1e-300:
            continue
        t, u = np.linalg.solve(mat, a[i] - w)
        if t > 0 and -1e-12 <= u <= 1 + 1e-12 and t < best[0]:
            purple = i == len(a) - 2
            best = (t, None if purple else 360 + i + u, purple)
    return best


for xy, white in [((0.2, 0.6), THIRD), ((0.3, 0.15), THIRD), ((0.45, 0.4), THIRD), ((0.15, 0.1), THIRD),
                  ((0.25, 0.3), [0.3127, 0.329]), ((0.5, 0.25), [0.3127, 0.329]), ((0.36, 0.55), THIRD)]:
    w = np.array(white, float)
    d = np.array(xy, float) - w
    t, lam, purple = first_crossing(w, d)
    tc, lamc, purple_c = first_crossing(w, -d)
    exp = {"purity": f(1 / t), "on_purple_line": purple,
           "complementary_nm": None if purple_c else f(lamc),
           "lambda_nm": f(-lamc) if purple else f(lam), "boundary": [f(v) for v in w + t * d]}
    case("dominant-wavelength", {"x": xy[0], "y": xy[1], "white": white}, exp,
         "numpy: 2x2 solves against the 1 nm locus polyline of colour-science CIE 1931 + purple line")
error("dominant-wavelength", {"x": 1 / 3, "y": 1 / 3}, "C = white point")

for a, b in [([0.64, 0.33, 0.2126], [0.3, 0.6, 0.7152]), ([0.2, 0.7, 1.0], [0.6, 0.3, 3.0]),
             ([0.3, 0.3, 0.0], [0.4, 0.5, 1.0])]:
    r = colour.XYZ_to_xyY(colour.xyY_to_XYZ(np.array(a)) + colour.xyY_to_XYZ(np.array(b)))
    case("mix", {"xyY_a": a, "xyY_b": b}, {"x": f(r[0]), "y": f(r[1]), "Y": f(r[2])},
         "colour.xyY_to_XYZ, add, colour.XYZ_to_xyY")
error("mix", {"xyY_a": [0.3, 0.0, 1.0], "xyY_b": [0.3, 0.3, 1.0]}, "y = 0 with Y != 0")

WIDE = [[0.708, 0.292], [0.170, 0.797], [0.131, 0.046]]  # ITU-R BT.2020
for xy, prim in [((0.3, 0.3), SRGB), ((0.2, 0.7), SRGB), ((0.64, 0.33), SRGB), ((0.2, 0.7), WIDE),
                 ((0.7, 0.2), WIDE)]:
    mat = np.vstack([np.array(prim, float).T, np.ones(3)])
    bary = np.linalg.solve(mat, np.array([xy[0], xy[1], 1.0]))
    case("in-gamut", {"x": xy[0], "y": xy[1], "primaries": prim},
         {"inside": bool(np.all(bary >= -1e-15)), "barycentric": [f(v) for v in bary]},
         "numpy.linalg.solve of [P; 1 1 1] l = [c; 1]")
error("in-gamut", {"x": 0.3, "y": 0.3, "primaries": [[0, 0], [0.5, 0.5], [1, 1]]}, "collinear primaries")


def seg_closest(c, a, b):
    e = b - a
    u = np.clip(np.dot(c - a, e) / np.dot(e, e), 0, 1)
    return a + u * e


for xy, prim, white, method in [((0.2, 0.7), SRGB, THIRD, "toward-white"), ((0.7, 0.25), SRGB, THIRD, "toward-white"),
                                ((0.1, 0.02), SRGB, [0.3127, 0.329], "toward-white"),
                                ((0.2, 0.7), SRGB, THIRD, "nearest"), ((0.7, 0.25), SRGB, THIRD, "nearest"),
                                ((0.3, 0.3), SRGB, THIRD, "nearest"), ((0.08, 0.85), WIDE, THIRD, "toward-white")]:
    c, w, P = np.array(xy, float), np.array(white, float), np.array(prim, float)
    mat = np.vstack([P.T, np.ones(3)])
    bary = np.linalg.solve(mat, np.array([c[0], c[1], 1.0]))
    if np.all(bary >= 0):
        r = c
    elif method == "nearest":
        cands = [seg_closest(c, P[i], P[(i + 1) % 3]) for i in range(3)]
        r = min(cands, key=lambda q: np.linalg.norm(q - c))
    else:  # the exit point of the segment white -> c through the triangle's edges
        ts = []
        for i in range(3):
            a, b = P[i], P[(i + 1) % 3]
            m2 = np.array([[c[0] - w[0], a[0] - b[0]], [c[1] - w[1], a[1] - b[1]]])
            if abs(np.linalg.det(m2)) > 1e-300:
                s, u = np.linalg.solve(m2, a - w)
                if 0 < s <= 1 and -1e-12 <= u <= 1 + 1e-12:
                    ts.append(s)
        r = w + min(ts) * (c - w)
    case("gamut-map", {"x": xy[0], "y": xy[1], "primaries": prim, "white": white, "method": method},
         {"x": f(r[0]), "y": f(r[1]), "shift": f(np.linalg.norm(r - c)), "moved": bool(np.any(r != c))},
         "numpy: edge intersection by 2x2 solve (toward-white) / projection on the edges (nearest)")
error("gamut-map", {"x": 0.2, "y": 0.7, "white": [0.9, 0.05]}, "white outside the triangle")
error("gamut-map", {"x": 0.2, "y": 0.7, "method": "clip"}, "bad method")

out = os.path.join(ROOT, "tests", "data", "formula_cases_color.jsonl")
os.makedirs(os.path.dirname(out), exist_ok=True)
with open(out, "w") as fh:
    for c in CASES:
        fh.write(json.dumps(c, ensure_ascii=False) + "\n")
print("wrote", len(CASES), "cases to", out)
