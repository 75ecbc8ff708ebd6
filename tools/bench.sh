#!/bin/sh
# `make bench`: whole-process and render times of `refray render` on the canonical whitted scene
# (shared/bench/SCENES.md §2) and on every SPD scene, median of 3 runs each, printed as a table
# with the command that reproduces each row. The POV-Ray 3.7 anchor of SCENES.md (2 threads,
# same machine kind) is printed beside the whitted rows.
set -e
bin=${1:-build/refray}
runs=${RUNS:-3}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# median of the numbers on stdin
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }

# bench NAME SCENE ARGS...: prints "wall render mrays" (medians)
bench() {
    scene=$1; shift
    : > "$tmp/wall"; : > "$tmp/render"; : > "$tmp/mrays"
    i=0
    while [ $i -lt "$runs" ]; do
        s=$(date +%s.%N)
        "$bin" render "$scene" -o "$tmp/out.exr" "$@" 2> "$tmp/log"
        e=$(date +%s.%N)
        awk -v s="$s" -v e="$e" "BEGIN {print e - s}" >> "$tmp/wall"
        sed -n 's/.* trace \([0-9.]*\) s, \([0-9.]*\) Mrays\/s.*/\1/p' "$tmp/log" >> "$tmp/render"
        sed -n 's/.* trace \([0-9.]*\) s, \([0-9.]*\) Mrays\/s.*/\2/p' "$tmp/log" >> "$tmp/mrays"
        i=$((i + 1))
    done
    printf "%8.3f %8.3f %8.2f" "$(median < "$tmp/wall")" "$(median < "$tmp/render")" "$(median < "$tmp/mrays")"
}

echo "refray bench on $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores; medians of $runs runs"
echo
printf "%-28s %8s %8s %8s  %s\n" "scene" "wall s" "render s" "Mrays/s" "POV-Ray 3.7 anchor (wall, 2 threads)"
for t in 1 2; do
    printf "%-28s %s  %s\n" "whitted 640x480 1spp ${t}thr" "$(bench scenes/whitted.rf --threads $t)" \
        "$([ $t = 2 ] && echo '0.062 s render (0.68 s start-up idle)')"
    printf "%-28s %s  %s\n" "whitted 640x480 16spp ${t}thr" "$(bench scenes/whitted.rf --threads $t --samples 16)" \
        "$([ $t = 2 ] && echo '0.88 s')"
done
for s in scenes/spd/*.nff scenes/spd/*.nff.gz; do
    n=$(basename "$s" | sed 's/\.nff.*//')
    printf "%-28s %s\n" "$n 512x512 1spp 2thr" "$(bench "$s" --threads 2)"
done
echo
echo "reproduce a row: time $bin render SCENE -o out.exr --threads T [--samples N]"

# The independent anchor on this machine: POV-Ray 3.7 on the same whitted scene
# (scenes/bench/whitted.pov, from SCENES.md), timed the same way and diffed against refray.
if command -v povray >/dev/null 2>&1; then
    echo
    : > "$tmp/wall"
    i=0
    while [ $i -lt "$runs" ]; do
        s=$(date +%s.%N)
        povray +Iscenes/bench/whitted.pov +O"$tmp/pov.exr" +FE +W640 +H480 -A -D +WT2 >/dev/null 2>&1
        e=$(date +%s.%N)
        awk -v s="$s" -v e="$e" "BEGIN {print e - s}" >> "$tmp/wall"
        i=$((i + 1))
    done
    printf "%-28s %8.3f  (povray +Iscenes/bench/whitted.pov +FE +W640 +H480 -A +WT2)\n" \
        "POV-Ray whitted 1spp 2thr" "$(median < "$tmp/wall")"
    "$bin" render scenes/whitted.rf -o "$tmp/out.exr" --quiet
    echo "refray against POV-Ray (POV-Ray writes half floats, ~5e-4 relative):"
    "$bin" diff "$tmp/out.exr" "$tmp/pov.exr" --kv | grep -E '^all\.(max_abs|mean_abs|rmse|pct_above_255)=' | sed 's/^/  /' || true
else
    echo "(POV-Ray is not installed: apt-get install povray adds the independent anchor row)"
fi
