#!/usr/bin/env python3
"""nff2pov: an NFF scene as a POV-Ray 3.7 scene with refray's NFF conventions, so that POV-Ray
can check refray's full renders independently (tests/test_povray.c; docs/scene-format.md, "How
NFF maps onto the model"). Written from the NFF text alone, not from refray's parser, so a
parsing slip in refray shows up as a difference too.

The conventions it reproduces (the SPD's own POV-Ray output differs in the first three):
  - angle A spans the centres of the outermost pixels: half-height tan(A/2) H/(H-1) at d = 1;
  - `l x y z` has intensity 1/sqrt(number of lights), no falloff;
  - no ambient term; `f r g b Kd Ks Shine T ior`: diffuse Kd (r,g,b), a white Phong highlight Ks
    with exponent Shine, mirror reflection Ks;
  - linear light throughout (assumed_gamma 1, EXR output), no adaptive depth cut-off
    (adc_bailout 0), and the trace depth given by --depth.
Refused (exit 2): T > 0 (POV-Ray's transmit also dims the surface colour, refray's kt does not)
and `pp` patches (their normal interpolation is refray's own).

Usage: tools/nff2pov.py SCENE.nff [--depth D] [--size W H] [-o OUT.pov]; writes the resolution
as a comment `// resolution W H`.
"""
import argparse
import gzip
import math
import sys


def fail(path, line, msg):
    print(f"{path}:{line}: {msg}", file=sys.stderr)
    sys.exit(2)


def tokens(path):
    """(token, line) pairs; `l` lines are kept whole, as their optional colour is per line."""
    opener = gzip.open if path.endswith(".gz") else open
    with opener(path, "rt") as f:
        for n, text in enumerate(f, 1):
            text = text.split("#", 1)[0]
            for t in text.split():
                yield t, n


def sub(a, b):
    return [a[i] - b[i] for i in range(3)]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def dot(a, b):
    return sum(a[i] * b[i] for i in range(3))


def unit(a):
    n = math.sqrt(dot(a, a))
    return [x / n for x in a]


def vec(v):
    return "<%.17g, %.17g, %.17g>" % tuple(v)


def convert(path, depth, size=None):
    toks = list(tokens(path))
    # the `l` lines with their colours: group tokens by line
    by_line = {}
    for t, n in toks:
        by_line.setdefault(n, []).append(t)
    pos = 0
    out, lights, objects = [], [], []
    cam = {"hither": 0.0, "resolution": (512, 512)}
    background = [0.0, 0.0, 0.0]
    texture = "texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 1 } }"

    def take(k):
        nonlocal pos
        if pos + k > len(toks):
            fail(path, toks[-1][1] if toks else 0, "unexpected end of file")
        vals = toks[pos:pos + k]
        pos += k
        try:
            return [float(t) for t, _ in vals]
        except ValueError:
            fail(path, vals[0][1], "expected %d numbers" % k)

    while pos < len(toks):
        word, line = toks[pos]
        pos += 1
        if word == "b":
            background = take(3)
        elif word == "v":
            for key in ("from", "at", "up", "angle"):
                if toks[pos][0] != key:
                    fail(path, toks[pos][1], "expected '%s'" % key)
                pos += 1
                cam[key] = take(1 if key == "angle" else 3)
            while pos < len(toks) and toks[pos][0] in ("hither", "resolution"):
                key = toks[pos][0]
                pos += 1
                cam[key] = take(1 if key == "hither" else 2)
        elif word == "l":
            rest = by_line[line][1:]
            vals = take(len(rest))
            if len(vals) not in (3, 6):
                fail(path, line, "a light has 3 or 6 numbers")
            lights.append(vals)
        elif word == "f":
            r, g, b, kd, ks, shine, t, _ior = take(8)
            if t > 0:
                fail(path, line, "T > 0 is not translated (POV-Ray's transmit dims the surface colour)")
            texture = ("texture { pigment { rgb <%.17g, %.17g, %.17g> } finish { ambient 0 diffuse %.17g "
                       "phong %.17g phong_size %.17g reflection %.17g } }" % (r, g, b, kd, ks, shine, ks))
        elif word == "s":
            x, y, z, rad = take(4)
            objects.append("sphere { %s, %.17g %s }" % (vec([x, y, z]), abs(rad), texture))
        elif word == "c":
            b = take(4)
            a = take(4)
            objects.append("cone { %s, %.17g, %s, %.17g open %s }" % (vec(b[:3]), abs(b[3]), vec(a[:3]), abs(a[3]), texture))
        elif word == "p":
            n = int(take(1)[0])
            vs = [take(3) for _ in range(n)]
            if n == 3:
                objects.append("triangle { %s, %s, %s %s }" % (vec(vs[0]), vec(vs[1]), vec(vs[2]), texture))
            else:
                objects.append("polygon { %d, %s %s }" % (n + 1, ", ".join(vec(v) for v in vs + vs[:1]), texture))
        elif word == "pp":
            fail(path, line, "pp patches are not translated")
        else:
            fail(path, line, "unknown NFF entity '%s'" % word)

    if "from" not in cam:
        fail(path, 0, "no viewpoint")
    w, h = size or (int(cam["resolution"][0]), int(cam["resolution"][1]))
    d = unit(sub(cam["at"], cam["from"]))
    upv = cam["up"]
    u = unit(sub(upv, [dot(upv, d) * x for x in d]))
    right = cross(d, u)  # right-handed: image x along dir x up
    half_h = math.tan(math.radians(cam["angle"][0]) / 2) * h / (h - 1)
    half_w = half_h * w / h
    inten = 1.0 / math.sqrt(len(lights)) if lights else 1.0
    out.append("// from %s by tools/nff2pov.py (refray's NFF conventions)" % path)
    out.append("// resolution %d %d" % (w, h))
    out.append("#version 3.7;")
    out.append("global_settings { assumed_gamma 1.0 max_trace_level %d adc_bailout 0 ambient_light 0 }" % depth)
    out.append("background { rgb %s }" % vec(background))
    out.append("camera { perspective location %s direction %s right %s up %s }" %
               (vec(cam["from"]), vec(d), vec([2 * half_w * x for x in right]), vec([2 * half_h * x for x in u])))
    for l in lights:
        c = l[3:] if len(l) == 6 else [inten] * 3
        out.append("light_source { %s color rgb %s }" % (vec(l[:3]), vec(c)))
    out.extend(objects)
    return "\n".join(out) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene")
    ap.add_argument("--depth", type=int, default=8)
    ap.add_argument("--size", type=int, nargs=2, metavar=("W", "H"),
                    help="the image size rendered (default: the scene's resolution); the field of view depends on it")
    ap.add_argument("-o", "--output")
    a = ap.parse_args()
    text = convert(a.scene, a.depth, tuple(a.size) if a.size else None)
    if a.output:
        with open(a.output, "w") as f:
            f.write(text)
    else:
        sys.stdout.write(text)


if __name__ == "__main__":
    main()
