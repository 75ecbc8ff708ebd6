#!/usr/bin/env python3
"""crosscheck.py -- `make crosscheck`: refray's full ray-traced images against two independent
renderers, Mitsuba 3 (scalar_rgb, path tracer) and POV-Ray 3.7 (Whitted tracer), on the scenes of
scenes/crosscheck/ (diffuse, mirror, glass, placed), exported by `refray export` (docs/crosscheck.md).

Mitsuba is a Monte-Carlo renderer, so its image is compared statistically:
  - Mitsuba renders N independent 1-sample passes (seeds 0 .. N-1, the `independent` sampler,
    box filter): each pixel gets N i.i.d. samples; their mean is the image and s^2/N its variance.
  - refray renders the same N samples per pixel with `--sampler random` (i.i.d. too, so its
    `--variance` s^2/N is exact, not the overestimate stratified samples give).
  - `refray diff --stat`: a z-test per pixel and channel, alpha 0.01 with Sidak's correction
    over the pixels, PASS when >= 99.75 % of the pixels accept (Mitsuba 3's own recipe).
  - and a global test: the mean over the image of (Mitsuba - refray) per channel against its
    standard error sqrt(sum of both variances) / pixels; |z| <= 4 passes. This one sees a bias
    of a fraction of a per cent over the whole image that the per-pixel test cannot.
POV-Ray is deterministic like refray: both at one sample per pixel centre (POV-Ray -A), compared
with `refray diff`: POV-Ray writes half floats (relative rounding 2^-11), so PASS when
max |difference| <= 1e-3 max(1, |value|) ... taken as max_abs <= 1e-3 and mean_abs <= 1.5e-4.

A scene that `refray export` refuses for a renderer (exit 2: something it cannot represent) is
not compared with that renderer, and the page says why.
Writes OUT/index.html (the images, heat maps, numbers and verdicts) and OUT/results.json; the
exit code is 1 when a comparison that ran failed. A renderer that is not installed is skipped and
said so (Mitsuba: `pip install mitsuba==3.5.2 numpy`, or run with --install, which installs it
into a venv of its own, ~/.cache/refray/mitsuba-venv, and uses it from then on; POV-Ray:
apt-get install povray).

usage: tools/crosscheck.py [--refray build/refray] [--out report/crosscheck] [--samples 1024]
                           [--install] [SCENE.rf[:WxH] ...]
(default: scenes/crosscheck/*.rf and scenes/soft.rf:128x128, whose area light and thin lens
Mitsuba checks and POV-Ray cannot represent)
"""
import argparse
import html
import importlib.util
import json
import math
import os
import re
import shutil
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MITSUBA_PIN = "mitsuba==3.5.2"  # the version tools/anchor_soft.py and this script were checked with
POV_MAX_ABS, POV_MEAN_ABS = 1e-3, 1.5e-4
GLOBAL_Z = 4.0


def say(msg):
    print("crosscheck: " + msg, file=sys.stderr, flush=True)


def run(cmd, **kw):
    return subprocess.run(cmd, capture_output=True, text=True, **kw)


def kv(text):
    out = {}
    for line in text.splitlines():
        if "=" in line:
            k, v = line.split("=", 1)
            out[k.strip()] = v.strip()
    return out


VENV = os.path.join(os.environ.get("XDG_CACHE_HOME") or os.path.expanduser("~/.cache"), "refray", "mitsuba-venv")


def venv_python(install):
    """Mitsuba from a venv of its own (pip may not install into a system Python, PEP 668): when
    VENV has it, or install is set and it can be made, this script runs again in it (no return)."""
    py = os.path.join(VENV, "bin", "python3")
    check = [py, "-c", "import mitsuba, numpy"]
    if not (os.path.exists(py) and subprocess.run(check, capture_output=True).returncode == 0):
        if not install:
            return
        say("installing %s and numpy into %s" % (MITSUBA_PIN, VENV))
        if not os.path.exists(py) and run([sys.executable, "-m", "venv", VENV]).returncode != 0:
            say("cannot make a venv (Debian: apt-get install python3-venv)")
            return
        p = run([py, "-m", "pip", "install", "--quiet", MITSUBA_PIN, "numpy"])
        if p.returncode != 0 or subprocess.run(check, capture_output=True).returncode != 0:
            say("pip could not install %s: %s" % (MITSUBA_PIN, (p.stderr or p.stdout).strip()[-300:]))
            return
    say("using Mitsuba from %s" % VENV)
    sys.stderr.flush()
    os.execv(py, [py, os.path.abspath(__file__)] + [x for x in sys.argv[1:] if x != "--install"])


def have_mitsuba():
    return importlib.util.find_spec("mitsuba") is not None and importlib.util.find_spec("numpy") is not None


def mitsuba_render(xml, samples, out_mean, out_var, out_png):
    """N one-sample passes: mean and variance of the mean per pixel, written as EXR."""
    import mitsuba as mi
    import numpy as np
    mi.set_variant("scalar_rgb")
    scene = mi.load_file(xml)
    s1 = s2 = None
    for seed in range(samples):
        img = np.array(mi.render(scene, spp=1, seed=seed), dtype=np.float64)[:, :, :3]
        s1 = img if s1 is None else s1 + img
        s2 = img * img if s2 is None else s2 + img * img
    mean = s1 / samples
    var = np.maximum(s2 - samples * mean * mean, 0.0) / (samples * (samples - 1))
    mi.Bitmap(mean.astype(np.float32)).write(out_mean)
    mi.Bitmap(var.astype(np.float32)).write(out_var)
    mi.Bitmap(mean.astype(np.float32)).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.UInt8, True).write(out_png)
    return mean, var


def exr_to_png(exr, png):
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    mi.Bitmap(exr).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.UInt8, True).write(png)


def read_exr(path):
    import mitsuba as mi
    import numpy as np
    return np.array(mi.Bitmap(path), dtype=np.float64)[:, :, :3]


def global_test(a, va, b, vb):
    """Per channel: mean(a - b) / (sqrt(sum(va + vb)) / n)."""
    import numpy as np
    n = a.shape[0] * a.shape[1]
    d = (a - b).reshape(n, 3).mean(axis=0)
    se = np.sqrt((va + vb).reshape(n, 3).sum(axis=0)) / n
    z = [float(d[c] / se[c]) if se[c] > 0 else (0.0 if d[c] == 0 else math.inf) for c in range(3)]
    ref = b.reshape(n, 3).mean(axis=0)
    return [float(x) for x in d], [float(x) for x in se], z, [float(x) for x in ref]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--refray", default=os.path.join(ROOT, "build", "refray"))
    ap.add_argument("--out", default=os.path.join(ROOT, "report", "crosscheck"))
    ap.add_argument("--samples", type=int, default=1024, help="samples per pixel for both (default 1024)")
    ap.add_argument("--install", action="store_true", help="pip install %s and numpy into a venv when missing" % MITSUBA_PIN)
    ap.add_argument("scenes", nargs="*")
    a = ap.parse_args()
    # SCENE or SCENE:WxH (rendered and exported at that size)
    # relative to the current folder (make's: the tree), so that messages name scenes as make does
    scenes = a.scenes or [os.path.relpath(x) for x in sorted(
        os.path.join(ROOT, "scenes", "crosscheck", f) for f in os.listdir(os.path.join(ROOT, "scenes", "crosscheck"))
        if f.endswith(".rf"))] + [os.path.relpath(os.path.join(ROOT, "scenes", "soft.rf")) + ":128x128"]
    os.makedirs(a.out, exist_ok=True)
    if not have_mitsuba():
        venv_python(a.install)  # re-runs this script in the venv when Mitsuba is (or gets) there
    use_mi = have_mitsuba()
    if not use_mi:
        say("Mitsuba 3 is not installed: its comparisons are skipped (%s -m pip install %s numpy, or make "
            "crosscheck CROSSCHECK_INSTALL=1, which installs it into %s)" % (sys.executable, MITSUBA_PIN, VENV))
    use_pov = shutil.which("povray") is not None
    if not use_pov:
        say("POV-Ray is not installed: skipped (apt-get install povray)")
    results, failed = [], 0
    for scene in scenes:
        size = []
        m = re.match(r"^(.*):(\d+)x(\d+)$", scene)
        if m:
            scene, size = m.group(1), ["--width", m.group(2), "--height", m.group(3)]
        name = os.path.splitext(os.path.basename(scene))[0]
        rel = os.path.relpath(scene, ROOT)
        r = {"scene": rel, "name": name}
        o = lambda suffix: os.path.join(a.out, name + suffix)
        t0 = time.time()
        p = run([a.refray, "render", scene] + size + ["--samples", str(a.samples), "--sampler", "random", "--seed", "1",
                 "-o", o(".refray.exr"), "--variance", o(".refray-var.exr"), "--png", o(".refray.png"), "--quiet"])
        if p.returncode != 0:
            say("%s: refray render failed: %s" % (rel, p.stderr.strip()))
            r["error"] = "refray render: " + p.stderr.strip()
            failed += 1
            results.append(r)
            continue
        r["refray_seconds"] = round(time.time() - t0, 2)
        if use_mi:
            p = run([a.refray, "export", "--quiet", "--mitsuba", o(".mitsuba.xml"), scene, "--samples", "1"] + size)
            if p.returncode == 2:  # refused: the scene holds what Mitsuba cannot represent
                r["mitsuba"] = {"skipped": p.stderr.strip()}
                say("%s: Mitsuba: not exportable, skipped (%s)" % (name, p.stderr.strip().splitlines()[0]))
            elif p.returncode != 0:
                r["mitsuba"] = {"error": "refray export --mitsuba: " + p.stderr.strip()}
                failed += 1
            else:
                t0 = time.time()
                mean, var = mitsuba_render(o(".mitsuba.xml"), a.samples, o(".mitsuba.exr"), o(".mitsuba-var.exr"),
                                           o(".mitsuba.png"))
                secs = round(time.time() - t0, 2)
                p = run([a.refray, "diff", o(".mitsuba.exr"), o(".refray.exr"), "--stat", "--var-a",
                         o(".mitsuba-var.exr"), "--var-b", o(".refray-var.exr"), "--kv", "--heatmap",
                         o(".mitsuba-p.png")])
                st = kv(p.stdout)
                plain = kv(run([a.refray, "diff", o(".mitsuba.exr"), o(".refray.exr"), "--kv"]).stdout)
                d, se, z, ref = global_test(mean, var, read_exr(o(".refray.exr")), read_exr(o(".refray-var.exr")))
                ok = st.get("verdict") == "PASS" and all(abs(x) <= GLOBAL_Z for x in z)
                failed += not ok
                r["mitsuba"] = {"seconds": secs, "stat": st, "mean_abs": plain.get("all.mean_abs"),
                                "max_abs": plain.get("all.max_abs"), "global_diff": d, "global_se": se,
                                "global_z": z, "refray_mean": ref, "verdict": "PASS" if ok else "FAIL"}
                say("%s: Mitsuba: %s of %s pixels accept (%s), image mean difference z = %s: %s" % (
                    name, st.get("accepted"), st.get("pixels"), st.get("verdict"),
                    ", ".join("%.2f" % x for x in z), r["mitsuba"]["verdict"]))
        if use_pov:
            p = run([a.refray, "export", "--quiet", "--pov", o(".pov"), scene] + size)
            if p.returncode == 2:
                r["povray"] = {"skipped": p.stderr.strip()}
                say("%s: POV-Ray: not exportable, skipped (%s)" % (name, p.stderr.strip().splitlines()[0]))
            elif p.returncode != 0:
                r["povray"] = {"error": "refray export --pov: " + p.stderr.strip()}
                failed += 1
            else:
                m = re.search(r"^// resolution (\d+) (\d+)", open(o(".pov")).read(), re.M)
                t0 = time.time()
                q = run(["povray", "+I" + o(".pov"), "+O" + o(".povray.exr"), "+FE", "+W" + m.group(1),
                         "+H" + m.group(2), "-A", "-D", "-V", "+WT2"])
                secs = round(time.time() - t0, 2)
                run([a.refray, "render", scene, "--samples", "1", "-o", o(".refray1.exr"), "--quiet"] + size)
                if q.returncode != 0:
                    r["povray"] = {"error": "povray: " + q.stderr.strip()[-500:]}
                    failed += 1
                else:
                    pd = kv(run([a.refray, "diff", o(".povray.exr"), o(".refray1.exr"), "--kv", "--heatmap",
                                 o(".povray-heat.png")]).stdout)
                    if use_mi:
                        exr_to_png(o(".povray.exr"), o(".povray.png"))
                    mx, mn = float(pd.get("all.max_abs", "inf")), float(pd.get("all.mean_abs", "inf"))
                    ok = mx <= POV_MAX_ABS and mn <= POV_MEAN_ABS
                    failed += not ok
                    r["povray"] = {"seconds": secs, "max_abs": mx, "mean_abs": mn,
                                   "pct_above_255": pd.get("all.pct_above_255"), "verdict": "PASS" if ok else "FAIL"}
                    say("%s: POV-Ray: max %.3g, mean %.3g: %s" % (name, mx, mn, r["povray"]["verdict"]))
        results.append(r)
    with open(os.path.join(a.out, "results.json"), "w") as f:
        json.dump({"samples": a.samples, "results": results}, f, indent=1)
    write_html(a, results, use_mi, use_pov)
    say("wrote %s" % os.path.join(a.out, "index.html"))
    return 1 if failed else 0


def write_html(a, results, use_mi, use_pov):
    e = html.escape
    rows, body = [], []
    for r in results:
        n = r["name"]
        mi_r, pv = r.get("mitsuba", {}), r.get("povray", {})

        def cell(x):
            if not x:
                return "<td>skipped</td>"
            if "error" in x:
                return "<td class=fail>ERROR</td>"
            if "skipped" in x:
                return "<td>not exportable</td>"
            return "<td class=%s>%s</td>" % (x["verdict"].lower(), x["verdict"])
        rows.append("<tr><td><a href='#%s'>%s</a></td>%s%s</tr>" % (n, e(n), cell(mi_r), cell(pv)))
        imgs = ["<figure><img src='%s.refray.png'><figcaption>refray (%d spp)</figcaption></figure>" % (n, a.samples)]
        notes = []
        if mi_r and "skipped" in mi_r:
            notes.append("<b>Mitsuba 3</b>: the scene cannot be exported: <pre>%s</pre>" % e(mi_r["skipped"]))
        elif mi_r and "error" not in mi_r:
            st = mi_r["stat"]
            imgs.append("<figure><img src='%s.mitsuba.png'><figcaption>Mitsuba 3 (%d spp)</figcaption></figure>" % (n, a.samples))
            imgs.append("<figure><img src='%s.mitsuba-p.png'><figcaption>z-test: -log10 p</figcaption></figure>" % n)
            notes.append("<b>Mitsuba 3</b> %s: per-pixel z-test %s of %s pixels accept (%.4f %%, needed 99.75 %%), "
                         "smallest p %s at (%s, %s); image mean per channel: refray %s, Mitsuba - refray %s "
                         "&plusmn; %s (z = %s, bound |z| &le; %g); mean |difference| %s, max %s; Mitsuba %s s." % (
                             mi_r["verdict"], st.get("accepted"), st.get("pixels"),
                             100 * float(st.get("accepted_share", 0)), st.get("min_p"), st.get("min_p_x"),
                             st.get("min_p_y"), fmt3(mi_r["refray_mean"]), fmt3(mi_r["global_diff"]),
                             fmt3(mi_r["global_se"]), ", ".join("%.2f" % x for x in mi_r["global_z"]), GLOBAL_Z,
                             mi_r["mean_abs"], mi_r["max_abs"], mi_r["seconds"]))
        elif mi_r:
            notes.append("<b>Mitsuba 3</b> ERROR: <pre>%s</pre>" % e(mi_r["error"]))
        if pv and "skipped" in pv:
            notes.append("<b>POV-Ray</b>: the scene cannot be exported: <pre>%s</pre>" % e(pv["skipped"]))
        elif pv and "error" not in pv:
            imgs.append("<figure><img src='%s.povray.png'><figcaption>POV-Ray 3.7 (1 spp)</figcaption></figure>" % n)
            imgs.append("<figure><img src='%s.povray-heat.png'><figcaption>|POV-Ray - refray|</figcaption></figure>" % n)
            notes.append("<b>POV-Ray 3.7</b> %s: max |difference| %.3g (bound %g), mean %.3g (bound %g) against "
                         "refray at 1 spp; POV-Ray %s s." % (pv["verdict"], pv["max_abs"], POV_MAX_ABS,
                                                              pv["mean_abs"], POV_MEAN_ABS, pv["seconds"]))
        elif pv:
            notes.append("<b>POV-Ray</b> ERROR: <pre>%s</pre>" % e(pv["error"]))
        if "error" in r:
            notes.append("<pre>%s</pre>" % e(r["error"]))
        body.append("<section id='%s'><h2>%s</h2><p>%s; files: <a href='%s.mitsuba.xml'>Mitsuba XML</a>, "
                    "<a href='%s.pov'>POV-Ray SDL</a></p><div class=imgs>%s</div><p>%s</p></section>" % (
                        n, e(n), e(r["scene"]), n, n, "".join(imgs), "<br>".join(notes)))
    skipped = []
    if not use_mi:
        skipped.append("Mitsuba 3 is not installed (pip install %s numpy)" % MITSUBA_PIN)
    if not use_pov:
        skipped.append("POV-Ray is not installed (apt-get install povray)")
    page = """<!DOCTYPE html><html><head><meta charset="utf-8"><title>refray: full ray-traced images against Mitsuba 3 and POV-Ray</title>
<style>body{font-family:sans-serif;max-width:70em;margin:auto}td,th{padding:2px 8px}.pass{color:#080}.fail{color:#b00}
.imgs{display:flex;flex-wrap:wrap}figure{margin:4px}img{image-rendering:pixelated;width:320px}</style></head><body>
<h1>Full ray-traced images against independent renderers</h1>
<p>made by <code>make crosscheck</code> (tools/crosscheck.py; docs/crosscheck.md explains the scenes and why the
compared quantities agree in expectation). Mitsuba 3 (scalar_rgb, path tracer): %d i.i.d. samples per pixel on
both sides, per-pixel z-test (alpha 0.01, Sidak, pass at 99.75 %%) and the image mean's z-score. POV-Ray 3.7:
1 sample at the pixel centre on both sides, half-float rounding bounds. %s</p>
<table><tr><th>scene</th><th>Mitsuba 3</th><th>POV-Ray 3.7</th></tr>%s</table>%s
<p><a href="../index.html">the local-mode report (tracer against the OpenGL rasterizer)</a></p></body></html>
""" % (a.samples, e("; ".join(skipped)), "".join(rows), "".join(body))
    with open(os.path.join(a.out, "index.html"), "w") as f:
        f.write(page)


def fmt3(v):
    return "(" + ", ".join("%.4g" % x for x in v) + ")"


if __name__ == "__main__":
    sys.exit(main())
