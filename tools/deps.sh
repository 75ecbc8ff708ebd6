#!/bin/sh
# refray's one set-up script. The Makefile runs it when a dependency is missing:
# as root it installs the Debian packages; otherwise it prints the one apt-get line and fails.
# Usage: tools/deps.sh check   (exit 0 when everything is present, quiet)
#        tools/deps.sh         (install or print the line)
#        tools/deps.sh bench   (the benchmark's anchors and tools, optional: Embree, POV-Ray, the CGAL
#                               demo data, gnuplot for the plot, python3-numpy for the anchor script;
#                               installed as root, else the line is printed; never fails)
#        tools/deps.sh test    (what some tests use when present, optional: POV-Ray for the
#                               independent full-render check, GNU parallel and Slurm's sbatch for
#                               the farm examples, python3 and python3-venv for make crosscheck's
#                               Mitsuba venv, Xvfb for the
#                               viewer's headless test; as `bench`)
set -u

# optional WHO WHAT FAILED MISSING PACKAGES...: packages that only some tests or the benchmark use,
# installed as root, else the apt-get line is printed (MISSING: a printf format given the list
# twice); never fails
optional() {
    who=$1 what=$2 failed=$3 missing=$4
    shift 4
    [ $# -eq 0 ] && exit 0
    m=" $*"
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
        echo "$who: installing $what:$m" >&2
        export DEBIAN_FRONTEND=noninteractive
        { apt-get update -qq && apt-get install -y -qq --no-install-recommends "$@"; } >/dev/null 2>&1 ||
            echo "$who: apt-get failed; $failed:$m" >&2
    else
        printf "%s: $missing\n" "$who" "$m" "$m" >&2
    fi
    exit 0
}

if [ "${1:-}" = test ]; then
    set --
    command -v povray >/dev/null 2>&1 || set -- "$@" povray
    command -v parallel >/dev/null 2>&1 || set -- "$@" parallel
    command -v sbatch >/dev/null 2>&1 || set -- "$@" slurm-client
    command -v python3 >/dev/null 2>&1 || set -- "$@" python3
    python3 -c 'import ensurepip' >/dev/null 2>&1 || set -- "$@" python3-venv
    command -v xvfb-run >/dev/null 2>&1 || set -- "$@" xvfb xauth
    command -v xdotool >/dev/null 2>&1 || set -- "$@" xdotool
    optional "refray tests" "what some tests use" "those tests skip without" \
        "some tests skip without:%s (sudo apt-get install%s)" "$@"
fi

if [ "${1:-}" = bench ]; then
    set --
    [ -f /usr/include/embree3/rtcore.h ] || set -- "$@" libembree-dev
    command -v povray >/dev/null 2>&1 || set -- "$@" povray
    [ -f /usr/share/doc/libcgal-demo/data.tar.gz ] || set -- "$@" libcgal-demo
    command -v gnuplot >/dev/null 2>&1 || set -- "$@" gnuplot-nox
    python3 -c 'import numpy' >/dev/null 2>&1 || set -- "$@" python3-numpy
    optional "refray bench" "the anchors" "the benchmark runs without" \
        "the anchors are missing; for the full comparison run: sudo apt-get install%s%.0s" "$@"
fi
PACKAGES="build-essential pkg-config libcjson-dev libpng-dev libopenexr-dev libosmesa6-dev libegl-dev libegl-mesa0 \
libglfw3-dev libcgal-dev libgmp-dev libmpfr-dev libcairo2-dev libfontconfig-dev zlib1g-dev \
libstb-dev libnetpbm-dev libtiff-dev"

# pkg-config modules that the build links against; CGAL is header-only, so its header is checked.
missing() {
    for m in libcjson libpng OpenEXR osmesa egl glfw3 cairo fontconfig zlib stb netpbm libtiff-4; do
        pkg-config --exists "$m" 2>/dev/null || echo "$m"
    done
    [ -f /usr/include/CGAL/version.h ] || echo "CGAL"
    command -v cc >/dev/null 2>&1 || echo "cc"
}

command -v pkg-config >/dev/null 2>&1 || need_pkgconfig=1
m=$(missing | tr '\n' ' ')
if [ -z "$m" ] && [ -z "${need_pkgconfig:-}" ]; then
    exit 0
fi
[ "${1:-}" = check ] && exit 1

echo "refray: missing dependencies: ${m}" >&2
if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
    echo "refray: installing Debian packages: $PACKAGES" >&2
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq >&2 && apt-get install -y -qq --no-install-recommends $PACKAGES >&2 || {
        echo "refray: apt-get failed; install by hand: apt-get install $PACKAGES" >&2; exit 1; }
    m=$(missing | tr '\n' ' ')
    [ -z "$m" ] || { echo "refray: still missing after install: $m" >&2; exit 1; }
    exit 0
fi
echo "refray: run this once, then repeat the make command:" >&2
echo "  sudo apt-get install $PACKAGES" >&2
exit 1
