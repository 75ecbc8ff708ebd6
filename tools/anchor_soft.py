#!/usr/bin/env python3
"""anchor_soft.py -- the anchor side of the `soft` run-time-against-error benchmark.

The `soft` scene (shared SCENES.md section 3: area light + depth of field, direct light only,
512x512) is rendered by each available anchor renderer at several sample counts; every image is
compared with that renderer's OWN converged reference, and the whole-process wall time of each
render is measured.  The output (a table, the time to reach relMSE 1e-3, and a CSV with the
columns of `refray bench`: renderer,strategy,spp,seconds,rmse,relmse) can be plotted together
with refray's own curve.

Anchors (each is skipped with one line "(X not installed: how to install)" when missing):
  mitsuba-llvm    Mitsuba 3 `llvm_ad_rgb`, scenes/bench/soft_mitsuba.xml, `direct` integrator,
                  `stratified` sampler, spp = sample_count.               strategy "stratified"
  mitsuba-scalar  Mitsuba 3 `scalar_rgb`, same file and settings.          strategy "stratified"
  povray          POV-Ray 3.7, scenes/bench/soft.pov, spp = BLUR (focal-blur camera rays per
                  pixel, min = max, each at a jittered position of a 16x16 sub-pixel grid and a
                  jittered lens point), AL x AL jittered area-light grid per hit (default
                  --pov-al 2, i.e. 4 shadow rays per camera ray), antialiasing off (-A: focal
                  blur already supersamples the pixel).                    strategy "blur+al2x2"

What "seconds" is: the median over --runs runs of the wall time of ONE WHOLE PROCESS, from
spawn to exit, as SCENES.md measures anchors:
  Mitsuba: `python3 -c "import mitsuba; set_variant; load_file(spp=N); render(seed=0);
           Bitmap(img).write(out.exr)"`, so Python start-up, the import of mitsuba/drjit, scene
           loading, the LLVM JIT compilation (llvm_ad_rgb; drjit's on-disk kernel cache in
           ~/.drjit is warm after the first run, as it is for any user), rendering and writing
           the float32 EXR are all included.
  POV-Ray: `povray -D +FE +W512 +H512 -A Declare=BLUR=N Declare=AL=a`, so start-up (about
           0.7 s of it is POV-Ray's own idle start-up), parsing, rendering and writing the
           half-float EXR are included.
Each renderer runs with its default thread count (every core).  One untimed 1-spp warm-up
render per renderer comes first (file caches; it also checks that the renderer runs).

References: rendered once and cached as float32 .npy (+ .json with the settings) in --cache
(default scenes/bench/data/anchors/, git-ignored); the file name holds the settings, the
renderer version and a hash of the scene file, so a change of any of them makes a new one.
  Mitsuba: --ref-spp samples (default 4096) as passes of at most 256 spp with seeds
           1000, 1001, ... averaged (the timed renders use seed 0, so they are independent).
  POV-Ray: one render at BLUR = --ref-spp (default 2048) with the same AL.  POV-Ray has no seed:
           its sub-pixel positions (and their jitter) are fixed hashes of the pixel and the
           sample number, so the reference's first N sub-pixel positions are those of the
           N-spp image; its lens points come from one fixed grid per render (the first 37 are
           the same hexagonal grid for every BLUR >= 37); only the area-light jitter is random
           (and, with 2 threads, not repeatable).  So the reference noise is partly shared with
           the test image: the measured relMSE is about (1 - N/ref) times the true one, while
           Mitsuba's independent reference makes it about (1 + N/ref) times; at the 1e-3
           crossing (N <= 64) both factors are within a few per cent of 1.

Metrics (SCENES.md section 3), over all 512 x 512 x 3 values in float64, x = image,
r = reference:  RMSE = sqrt(mean((x - r)^2)),  relMSE = mean((x - r)^2 / (r^2 + 0.01)).
Time to reach relMSE T (--target, default 1e-3): log-log interpolation of seconds against relMSE
between the first pair of consecutive spp that brackets T; "<= t (at N spp)" when the smallest
spp is already below T; "not reached" otherwise.

Run time on the 2-core benchmark machine: the first run makes the references; measured once,
on a partly loaded machine: llvm 4096 spp 68 s, scalar 4096 spp 325 s, POV-Ray BLUR 2048 428 s,
17 min in all.  Every later run of the default invocation takes about 3.3 min (renders: llvm
15 s, scalar 57 s, POV-Ray 115 s).

Reading EXR: a small built-in reader (numpy + zlib) for scanline files with NONE, RLE, ZIPS or
ZIP compression and HALF/FLOAT/UINT channels; POV-Ray writes ZIP half-float files, so POV-Ray
needs no EXR library.  Files it cannot read (Mitsuba writes PIZ) go to mitsuba's own Bitmap
(OpenEXR inside), then to the `OpenEXR` pip package if that is installed.

Usage:  python3 tools/anchor_soft.py [--runs 3] [--spp 1 4 16 64 256] [--ref-spp N]
            [--cache DIR] [--csv PATH] [--only mitsuba-llvm|mitsuba-scalar|povray ...]
            [--pov-al 2] [--target 1e-3] [--install]
"""

import argparse
import hashlib
import importlib.util
import json
import math
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import time
import zlib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SCENE_XML = ROOT / "scenes" / "bench" / "soft_mitsuba.xml"
SCENE_POV = ROOT / "scenes" / "bench" / "soft.pov"
DEFAULT_CACHE = ROOT / "scenes" / "bench" / "data" / "anchors"
RENDERERS = ["mitsuba-llvm", "mitsuba-scalar", "povray"]
VARIANT = {"mitsuba-llvm": "llvm_ad_rgb", "mitsuba-scalar": "scalar_rgb"}
DEFAULT_REF = {"mitsuba-llvm": 4096, "mitsuba-scalar": 4096, "povray": 2048}
MITSUBA_PIN = "mitsuba==3.5.2"      # the version this script was written and checked with
REF_PASS = 256                      # Mitsuba reference pass size (a square: stratified)
REF_SEED0 = 1000
W = H = 512

# One timed Mitsuba render: argv = variant scene spp seed out.exr
MI_RENDER = (
    "import sys\n"
    "import mitsuba as mi\n"
    "mi.set_variant(sys.argv[1])\n"
    "scene = mi.load_file(sys.argv[2], spp=int(sys.argv[3]))\n"
    "img = mi.render(scene, seed=int(sys.argv[4]))\n"
    "mi.Bitmap(img).write(sys.argv[5])\n"
)

# A Mitsuba reference: argv = variant scene pass_spp passes seed0 out.npy
MI_REFERENCE = (
    "import sys\n"
    "import numpy as np\n"
    "import mitsuba as mi\n"
    "variant, scene, spp, passes, seed0, out = sys.argv[1:7]\n"
    "mi.set_variant(variant)\n"
    "scene = mi.load_file(scene, spp=int(spp))\n"
    "acc = None\n"
    "for i in range(int(passes)):\n"
    "    img = np.array(mi.render(scene, seed=int(seed0) + i), dtype=np.float64)\n"
    "    acc = img if acc is None else acc + img\n"
    "    print('pass %d/%s' % (i + 1, passes), file=sys.stderr, flush=True)\n"
    "np.save(out, (acc / int(passes)).astype(np.float32))\n"
)


def say(msg=""):
    print(msg, flush=True)


# ---- EXR reading ---------------------------------------------------------------------------

class ExrUnsupported(Exception):
    pass


def _exr_builtin(path):
    """Scanline EXR, compression NONE/RLE/ZIPS/ZIP, channels R,G,B (or Y): float32 HxWx3."""
    import numpy as np
    data = Path(path).read_bytes()
    if data[:4] != b"\x76\x2f\x31\x01":
        raise ExrUnsupported("not an OpenEXR file")
    flags = struct.unpack_from("<I", data, 4)[0]
    if flags & (0x200 | 0x800 | 0x1000):
        raise ExrUnsupported("tiled, deep or multi-part file")
    pos, hdr = 8, {}
    while data[pos] != 0:
        end = data.index(b"\0", pos)
        name = data[pos:end].decode()
        end2 = data.index(b"\0", end + 1)
        typ = data[end + 1:end2].decode()
        size = struct.unpack_from("<i", data, end2 + 1)[0]
        hdr[name] = (typ, data[end2 + 5:end2 + 5 + size])
        pos = end2 + 5 + size
    pos += 1
    chans, raw = [], hdr["channels"][1]
    p = 0
    while raw[p] != 0:
        end = raw.index(b"\0", p)
        ptype, _, xs, ys = struct.unpack_from("<iB3xii", raw, end + 1)
        if xs != 1 or ys != 1:
            raise ExrUnsupported("sub-sampled channels")
        chans.append((raw[p:end].decode(), ptype))
        p = end + 1 + 16
    comp = hdr["compression"][1][0]
    lines = {0: 1, 1: 1, 2: 1, 3: 16}.get(comp)
    if lines is None:
        raise ExrUnsupported("compression %d" % comp)
    x0, y0, x1, y1 = struct.unpack("<iiii", hdr["dataWindow"][1])
    w, h = x1 - x0 + 1, y1 - y0 + 1
    dtypes = {0: np.dtype("<u4"), 1: np.dtype("<f2"), 2: np.dtype("<f4")}
    nblocks = (h + lines - 1) // lines
    offsets = struct.unpack_from("<%dQ" % nblocks, data, pos)
    planes = {name: np.empty((h, w), np.float32) for name, _ in chans}
    for off in offsets:
        y, size = struct.unpack_from("<ii", data, off)
        blob = data[off + 8:off + 8 + size]
        n = min(lines, y1 - y + 1)
        expect = n * w * sum(dtypes[t].itemsize for _, t in chans)
        if comp != 0 and size < expect:
            if comp == 1:
                buf, i = bytearray(), 0
                while i < len(blob):
                    c = struct.unpack_from("b", blob, i)[0]
                    if c < 0:
                        buf += blob[i + 1:i + 1 - c]
                        i += 1 - c
                    else:
                        buf += blob[i + 1:i + 2] * (c + 1)
                        i += 2
                t = np.frombuffer(bytes(buf), np.uint8)
            else:
                t = np.frombuffer(zlib.decompress(blob), np.uint8)
            if t.size != expect:
                raise ExrUnsupported("bad block size")
            # undo the predictor, then the two-half byte interleave (OpenEXR zip.cpp)
            d = t.astype(np.int64)
            d[1:] -= 128
            t = (np.cumsum(d) & 0xFF).astype(np.uint8)
            out = np.empty_like(t)
            half = (t.size + 1) // 2
            out[0::2] = t[:half]
            out[1::2] = t[half:]
            blob = out.tobytes()
        elif len(blob) != expect:
            raise ExrUnsupported("bad block size")
        p = 0
        for row in range(n):
            for name, typ in chans:
                dt = dtypes[typ]
                planes[name][y - y0 + row] = np.frombuffer(blob, dt, w, p)
                p += w * dt.itemsize
    if all(c in planes for c in "RGB"):
        return np.stack([planes["R"], planes["G"], planes["B"]], axis=-1)
    if "Y" in planes:
        return np.repeat(planes["Y"][:, :, None], 3, axis=2)
    raise ExrUnsupported("no R,G,B or Y channels")


_mi_reader = None


def read_exr(path):
    import numpy as np
    try:
        return _exr_builtin(path)
    except ExrUnsupported:
        pass
    global _mi_reader
    if importlib.util.find_spec("mitsuba") is not None:
        if _mi_reader is None:
            import mitsuba as mi
            mi.set_variant("scalar_rgb")
            _mi_reader = mi
        bmp = _mi_reader.Bitmap(str(path)).convert(
            _mi_reader.Bitmap.PixelFormat.RGB, _mi_reader.Struct.Type.Float32, False)
        return np.array(bmp, dtype=np.float32).reshape(bmp.height(), bmp.width(), 3)
    if importlib.util.find_spec("OpenEXR") is not None:
        import OpenEXR
        import Imath
        f = OpenEXR.InputFile(str(path))
        dw = f.header()["dataWindow"]
        w, h = dw.max.x - dw.min.x + 1, dw.max.y - dw.min.y + 1
        pt = Imath.PixelType(Imath.PixelType.FLOAT)
        return np.stack([np.frombuffer(f.channel(c, pt), np.float32).reshape(h, w)
                         for c in "RGB"], axis=-1)
    raise RuntimeError("cannot read %s: needs mitsuba or the OpenEXR package" % path)


# ---- metrics -------------------------------------------------------------------------------

def metrics(x, r):
    import numpy as np
    x = np.asarray(x, np.float64)
    r = np.asarray(r, np.float64)
    if x.shape != r.shape:
        raise RuntimeError("image shape %s differs from reference %s" % (x.shape, r.shape))
    d2 = (x - r) ** 2
    return math.sqrt(d2.mean()), float((d2 / (r * r + 0.01)).mean())


def time_to_target(points, target):
    """points: [(spp, seconds, relmse)] by spp. Returns (seconds or None, text)."""
    if not points:
        return None, "no data"
    if points[0][2] <= target:
        return points[0][1], "<= %.3f s (at %d spp)" % (points[0][1], points[0][0])
    for (n0, t0, e0), (n1, t1, e1) in zip(points, points[1:]):
        if e0 > target >= e1:
            if e1 <= 0 or t0 <= 0 or t1 <= 0:
                return t1, "%.3f s (at %d spp)" % (t1, n1)
            f = (math.log(target) - math.log(e0)) / (math.log(e1) - math.log(e0))
            t = math.exp(math.log(t0) + f * (math.log(t1) - math.log(t0)))
            return t, "%.3f s (between %d and %d spp)" % (t, n0, n1)
    return None, "not reached (relMSE %.3g at %d spp)" % (points[-1][2], points[-1][0])


# ---- renderers -----------------------------------------------------------------------------

def run(cmd, log, cwd=None):
    """Run one whole process; returns its wall time in seconds. Raises on failure."""
    with open(log, "wb") as f:
        t0 = time.perf_counter()
        rc = subprocess.run(cmd, stdin=subprocess.DEVNULL, stdout=f, stderr=subprocess.STDOUT,
                            cwd=cwd).returncode
        t = time.perf_counter() - t0
    if rc != 0:
        tail = Path(log).read_text(errors="replace").strip().splitlines()[-5:]
        raise RuntimeError("exit %d: %s" % (rc, " | ".join(tail)))
    return t


def file_hash(path):
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()[:12]


class Mitsuba:
    def __init__(self, name, tmp):
        self.name, self.variant, self.tmp = name, VARIANT[name], tmp
        self.scene = SCENE_XML
        self.strategy = "stratified"
        from importlib.metadata import version
        self.version = version("mitsuba")

    def render(self, spp, out):
        cmd = [sys.executable, "-c", MI_RENDER, self.variant, str(self.scene), str(spp), "0",
               str(out)]
        return run(cmd, self.tmp / "log.txt")

    def ref_key(self, ref_spp):
        return "soft_ref_%s_%dspp_mitsuba%s_%s" % (self.name, ref_spp, self.version,
                                                   file_hash(self.scene))

    def make_reference(self, ref_spp, out_npy):
        per = REF_PASS if ref_spp % REF_PASS == 0 else ref_spp
        passes = ref_spp // per
        say("  %s reference: %d spp = %d pass(es) of %d spp, seeds %d.. (one process)"
            % (self.name, ref_spp, passes, per, REF_SEED0))
        cmd = [sys.executable, "-c", MI_REFERENCE, self.variant, str(self.scene), str(per),
               str(passes), str(REF_SEED0), str(out_npy)]
        return run(cmd, self.tmp / "reflog.txt")


class Povray:
    def __init__(self, tmp, al):
        self.name, self.tmp, self.al = "povray", tmp, al
        self.strategy = "blur+al%dx%d" % (al, al)
        # POV-Ray's Debian povray.conf restricts file I/O to a few folders; /tmp is one, so the
        # scene is copied next to the output (the copy is identical).
        self.scene = tmp / "soft.pov"
        shutil.copyfile(SCENE_POV, self.scene)
        out = subprocess.run([self.exe(), "--version"], stdout=subprocess.PIPE,
                             stderr=subprocess.STDOUT).stdout.decode(errors="replace")
        ver = [tok for tok in out.split() if tok[:2] == "3."]
        self.version = ver[0] if ver else "unknown"

    @staticmethod
    def exe():
        return shutil.which("povray")

    def cmd(self, blur, out):
        return [self.exe(), "-D", "+I" + str(self.scene), "+O" + str(out), "+FE",
                "+W%d" % W, "+H%d" % H, "-A", "Declare=BLUR=%d" % blur,
                "Declare=AL=%d" % self.al]

    def render(self, spp, out):
        return run(self.cmd(spp, out), self.tmp / "log.txt", cwd=self.tmp)

    def ref_key(self, ref_spp):
        return "soft_ref_povray_blur%d_al%d_pov%s_%s" % (ref_spp, self.al, self.version,
                                                          file_hash(SCENE_POV))

    def make_reference(self, ref_spp, out_npy):
        import numpy as np
        say("  povray reference: BLUR=%d, AL=%d (one render)" % (ref_spp, self.al))
        exr = self.tmp / "ref.exr"
        t = run(self.cmd(ref_spp, exr), self.tmp / "reflog.txt", cwd=self.tmp)
        np.save(out_npy, read_exr(exr))
        return t


def load_reference(r, ref_spp, cache):
    import numpy as np
    key = r.ref_key(ref_spp)
    npy, meta = cache / (key + ".npy"), cache / (key + ".json")
    if npy.exists() and meta.exists():
        info = json.loads(meta.read_text())
        say("  %s reference: cached %s (made in %.1f s)" % (r.name, npy.name, info["seconds"]))
        return np.load(npy), info
    cache.mkdir(parents=True, exist_ok=True)
    tmp_npy = r.tmp / (key + ".npy")
    t = r.make_reference(ref_spp, tmp_npy)
    img = np.load(tmp_npy)
    if img.shape != (H, W, 3) or not np.all(np.isfinite(img)):
        raise RuntimeError("reference image is %s or not finite" % (img.shape,))
    shutil.move(str(tmp_npy), str(npy))
    info = {"renderer": r.name, "strategy": r.strategy, "ref_spp": ref_spp,
            "version": r.version, "seconds": round(t, 3), "scene_sha256_12": key[-12:]}
    if isinstance(r, Povray):
        info["al"] = r.al
    meta.write_text(json.dumps(info, indent=1) + "\n")
    say("  %s reference: made in %.1f s -> %s" % (r.name, t, npy))
    return img, info


# ---- main ----------------------------------------------------------------------------------

def pip_install(pkg):
    say("installing %s: %s -m pip install %s" % (pkg, sys.executable, pkg))
    subprocess.run([sys.executable, "-m", "pip", "install", pkg], check=False)


def main():
    ap = argparse.ArgumentParser(
        description="Anchor renderers (Mitsuba 3, POV-Ray 3.7) on the `soft` scene: whole-"
                    "process time against RMSE/relMSE to each renderer's own reference.")
    ap.add_argument("--runs", type=int, default=3, help="timed runs per point (median), default 3")
    ap.add_argument("--spp", nargs="+", default=["1", "4", "16", "64", "256"],
                    help="sample counts (space- or comma-separated), default 1 4 16 64 256")
    ap.add_argument("--ref-spp", type=int, default=None,
                    help="reference spp for every selected renderer (default: Mitsuba 4096, "
                         "POV-Ray BLUR 2048)")
    ap.add_argument("--cache", type=Path, default=DEFAULT_CACHE,
                    help="reference cache folder (default scenes/bench/data/anchors/)")
    ap.add_argument("--csv", type=Path, default=None,
                    help="write renderer,strategy,spp,seconds,rmse,relmse to this file")
    ap.add_argument("--only", action="append", default=None, metavar="RENDERER",
                    help="mitsuba-llvm, mitsuba-scalar or povray (repeat or comma-separate)")
    ap.add_argument("--pov-al", type=int, default=2,
                    help="POV-Ray area-light grid AL x AL (power of two), default 2")
    ap.add_argument("--target", type=float, default=1e-3, help="relMSE target, default 1e-3")
    ap.add_argument("--install", action="store_true",
                    help="pip install numpy and %s into this Python if missing" % MITSUBA_PIN)
    a = ap.parse_args()

    spps = sorted({int(s) for item in a.spp for s in item.split(",") if s.strip()})
    if not spps or spps[0] < 1 or a.runs < 1:
        ap.error("spp values and --runs must be >= 1")
    only = RENDERERS
    if a.only:
        only = [s.strip() for item in a.only for s in item.split(",") if s.strip()]
        bad = [s for s in only if s not in RENDERERS]
        if bad:
            ap.error("unknown renderer %s (choose from %s)"
                     % (", ".join(bad), ", ".join(RENDERERS)))
    if a.ref_spp is not None and (a.ref_spp < 1 or (
            any(s.startswith("mitsuba") for s in only) and a.ref_spp % REF_PASS != 0 and
            math.isqrt(a.ref_spp) ** 2 != a.ref_spp)):
        ap.error("--ref-spp must be >= 1, and for Mitsuba a square or a multiple of %d "
                 "(stratified sampler)" % REF_PASS)

    if a.install:
        if importlib.util.find_spec("numpy") is None:
            pip_install("numpy")
        if importlib.util.find_spec("mitsuba") is None and \
                any(s.startswith("mitsuba") for s in only):
            pip_install(MITSUBA_PIN)
        importlib.invalidate_caches()
    if importlib.util.find_spec("numpy") is None:
        say("(numpy not installed: pip install numpy, or rerun with --install)")
        return 0
    import numpy as np  # noqa: F401

    t_start = time.perf_counter()
    tmp = Path(tempfile.mkdtemp(prefix="anchor_soft_"))
    try:
        renderers = []
        have_mi = importlib.util.find_spec("mitsuba") is not None
        for name in RENDERERS:
            if name not in only:
                continue
            if name.startswith("mitsuba") and not have_mi:
                say("(%s not installed: pip install %s, or rerun with --install)"
                    % (name, MITSUBA_PIN))
                continue
            if name == "povray" and Povray.exe() is None:
                say("(povray not installed: apt-get install povray)")
                continue
            if name == "povray" and (a.pov_al < 2 or a.pov_al & (a.pov_al - 1)):
                ap.error("--pov-al must be a power of two >= 2 (soft.pov header)")
            sub = tmp / name
            sub.mkdir()
            r = Povray(sub, a.pov_al) if name == "povray" else Mitsuba(name, sub)
            try:        # untimed warm-up, which also checks that the renderer works here
                r.render(1, sub / "warmup.exr")
                read_exr(sub / "warmup.exr")
            except Exception as e:  # noqa: BLE001
                hint = ""
                if name == "mitsuba-llvm":
                    hint = "; llvm_ad_rgb needs libLLVM: apt-get install libllvm15"
                say("(%s does not run here: %s%s)" % (name, str(e)[:200], hint))
                continue
            renderers.append(r)
        if not renderers:
            say("no anchor renderer available")
            return 0

        say("anchor_soft: scene soft (SCENES.md section 3), %dx%d; seconds = whole-process wall "
            "time, median of %d run(s); errors against each renderer's own reference"
            % (W, H, a.runs))
        say("  %d cores, load average %.2f at start" % (os.cpu_count() or 0, os.getloadavg()[0]))
        refs, rows = {}, []
        for r in renderers:
            ref_spp = a.ref_spp or DEFAULT_REF[r.name]
            refs[r.name] = load_reference(r, ref_spp, a.cache)
        if any(r.name.startswith("mitsuba") for r in renderers) and \
                any(math.isqrt(n) ** 2 != n for n in spps):
            say("  (note: Mitsuba's stratified sampler rounds a non-square spp to a square)")

        say()
        say("%-15s %6s %9s %11s %11s" % ("renderer", "spp", "seconds", "RMSE", "relMSE"))
        for r in renderers:
            ref = refs[r.name][0]
            for n in spps:
                times, errs = [], []
                for k in range(a.runs):
                    out = r.tmp / ("img_%d_%d.exr" % (n, k))
                    times.append(r.render(n, out))
                    errs.append(metrics(read_exr(out), ref))
                    out.unlink()
                sec = float(np.median(times))
                rmse = float(np.median([e[0] for e in errs]))
                rel = float(np.median([e[1] for e in errs]))
                rows.append((r.name, r.strategy, n, sec, rmse, rel))
                say("%-15s %6d %9.3f %11.4e %11.4e" % (r.name, n, sec, rmse, rel))

        say()
        say("time to relMSE %.0e (log-log interpolation between bracketing spp):" % a.target)
        for r in renderers:
            pts = [(n, s, e) for (name, _, n, s, _, e) in rows if name == r.name]
            say("%-15s %s" % (r.name, time_to_target(pts, a.target)[1]))

        say()
        say("references:")
        first = None
        for r in renderers:
            img, info = refs[r.name]
            if r.name == "povray":
                desc = "BLUR %d, AL %d, POV-Ray %s" % (info["ref_spp"], info["al"], info["version"])
            else:
                desc = "%d spp, Mitsuba %s" % (info["ref_spp"], info["version"])
            line = "%-15s %s, made in %.1f s" % (r.name, desc, info["seconds"])
            if first is None:
                first = (r.name, img)
            else:
                rm, rel = metrics(img, first[1])
                line += "; against %s's: RMSE %.4e relMSE %.4e" % (first[0], rm, rel)
            say(line)

        if a.csv:
            a.csv.parent.mkdir(parents=True, exist_ok=True)
            with open(a.csv, "w") as f:
                f.write("renderer,strategy,spp,seconds,rmse,relmse\n")
                for row in rows:
                    f.write("%s,%s,%d,%.6f,%.6e,%.6e\n" % row)
            say("wrote %s" % a.csv)
        say("total %.1f s" % (time.perf_counter() - t_start))
        return 0
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    try:
        sys.exit(main())
    except RuntimeError as e:
        say("anchor_soft: error: %s" % e)
        sys.exit(1)
