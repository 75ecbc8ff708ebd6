#!/bin/sh
# `make bench`: refray's run times against the anchors of shared/bench/SCENES.md, each section
# with the command that reproduces it (docs/performance.md explains the numbers).
#  1. mesh: the intersection core against Embree 3 on the very same rays (compare/mesh_bench.c);
#     the 1.2 M-triangle bunny is made here when missing (CGAL Loop subdivision of Debian's
#     libcgal-demo bunny, compare/make_mesh.cpp) into scenes/bench/data/, which git ignores.
#  2. whitted and the SPD scenes: `refray render` wall, load, build and trace times.
#  3. POV-Ray 3.7 on the same whitted scene, and the image difference.
# Usage: tools/bench.sh [refray] [refray-mesh-bench] [refray-make-mesh]; RUNS=n (default 3).
set -e
bin=${1:-build/refray}
meshbench=${2:-build/refray-mesh-bench}
makemesh=${3:-build/refray-make-mesh}
runs=${RUNS:-3}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# median of the numbers on stdin
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }

echo "refray bench on $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores; medians of $runs runs"

# ---- 1. mesh against Embree ------------------------------------------------------------------
echo
echo "== 1. mesh: 1,206,528 triangles, 1024x768 primary + shadow rays, refray against Embree 3.13 (SCENES.md section 1)"
mesh=scenes/bench/data/bunny.obj
cgal=/usr/share/doc/libcgal-demo/data.tar.gz
if [ ! -f "$mesh" ] && [ -f "$cgal" ]; then
    echo "making $mesh (bunny00.off of libcgal-demo, 2 levels of Loop subdivision by CGAL)"
    mkdir -p "$(dirname "$mesh")"
    tar -xzf "$cgal" -C "$tmp" data/meshes/bunny00.off
    "$makemesh" "$tmp/data/meshes/bunny00.off" "$mesh"
fi
if [ -f "$mesh" ]; then
    "$meshbench" scenes/bench/mesh.rf --runs $((runs < 5 ? 5 : runs))
else
    echo "(skipped: the bunny comes from Debian's libcgal-demo: apt-get install libcgal-demo)"
fi

# ---- 2. whitted and SPD --------------------------------------------------------------------
# bench SCENE ARGS...: prints "wall load build trace mrays" (medians)
bench() {
    scene=$1; shift
    for f in wall load build trace mrays; do : > "$tmp/$f"; done
    i=0
    while [ $i -lt "$runs" ]; do
        s=$(date +%s.%N)
        "$bin" render "$scene" -o "$tmp/out.exr" "$@" 2> "$tmp/log"
        e=$(date +%s.%N)
        awk -v s="$s" -v e="$e" "BEGIN {print e - s}" >> "$tmp/wall"
        for f in load build trace; do
            sed -n "s/.* $f \([0-9.]*\) s.*/\1/p" "$tmp/log" >> "$tmp/$f"
        done
        sed -n 's/.* \([0-9.]*\) Mrays\/s.*/\1/p' "$tmp/log" >> "$tmp/mrays"
        i=$((i + 1))
    done
    printf "%8.3f %8.3f %8.3f %8.3f %8.2f" "$(median < "$tmp/wall")" "$(median < "$tmp/load")" \
        "$(median < "$tmp/build")" "$(median < "$tmp/trace")" "$(median < "$tmp/mrays")"
}

echo
echo "== 2. refray render: whitted (SCENES.md section 2) and the SPD scenes at 512x512, 1 spp"
printf "%-28s %8s %8s %8s %8s %8s\n" "scene" "wall s" "load s" "build s" "trace s" "Mrays/s"
for t in 1 2; do
    printf "%-28s %s\n" "whitted 640x480 1spp ${t}thr" "$(bench scenes/whitted.rf --threads $t)"
    printf "%-28s %s\n" "whitted 640x480 16spp ${t}thr" "$(bench scenes/whitted.rf --threads $t --samples 16)"
done
for s in scenes/spd/*.nff scenes/spd/*.nff.gz; do
    n=$(basename "$s" | sed 's/\.nff.*//')
    case $n in *-2) continue ;; esac # balls-2, teapot-2: the same scenes at another size
    for t in 1 2; do
        printf "%-28s %s\n" "$n 512x512 1spp ${t}thr" "$(bench "$s" --threads $t)"
    done
done
echo "Mrays/s: all rays of the render over the trace time. Reproduce a row:"
echo "  $bin render SCENE -o out.exr --threads T [--samples N]"

# ---- 3. POV-Ray on whitted -----------------------------------------------------------------
echo
if command -v povray >/dev/null 2>&1; then
    echo "== 3. POV-Ray 3.7 on the same whitted scene (scenes/bench/whitted.pov, from SCENES.md)"
    for t in 1 2; do
        : > "$tmp/wall"
        i=0
        while [ $i -lt "$runs" ]; do
            s=$(date +%s.%N)
            povray +Iscenes/bench/whitted.pov +O"$tmp/pov.exr" +FE +W640 +H480 -A -D +WT$t >/dev/null 2>&1
            e=$(date +%s.%N)
            awk -v s="$s" -v e="$e" "BEGIN {print e - s}" >> "$tmp/wall"
            i=$((i + 1))
        done
        printf "%-28s %8.3f  (povray +Iscenes/bench/whitted.pov +FE +W640 +H480 -A +WT%d, whole process)\n" \
            "POV-Ray whitted 1spp ${t}thr" "$(median < "$tmp/wall")" "$t"
    done
    "$bin" render scenes/whitted.rf -o "$tmp/out.exr" --quiet
    echo "refray against POV-Ray (POV-Ray writes half floats, ~5e-4 relative):"
    "$bin" diff "$tmp/out.exr" "$tmp/pov.exr" --kv | grep -E '^all\.(max_abs|mean_abs|rmse|pct_above_255)=' | sed 's/^/  /' || true
else
    echo "(POV-Ray is not installed: apt-get install povray adds the POV-Ray anchor)"
fi
