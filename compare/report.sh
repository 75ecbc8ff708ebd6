#!/bin/sh
# The cross-validation report (issue 5, `make report`): every scene in scenes/ (*.rf) and every
# SPD scene (scenes/spd/*.nff, *.nff.gz) rendered by `refray render --local` and by
# refray-raster, diffed with `refray diff` (silhouettes from both depth images), written to
# OUTDIR/index.html with relative links only (opens offline). Explanations of remaining
# differences come from compare/report-notes.txt ("scene-name: text" lines).
# usage: compare/report.sh REFRAY REFRAY-RASTER OUTDIR SIZE   (SIZE: longest image side, e.g. 320)
set -u
bin=$1 raster=$2 out=$3 size=${4%%x*}
notes=compare/report-notes.txt
case $size in '' | *[!0-9]*) echo "report.sh: SIZE must be a number of pixels" >&2; exit 5 ;; esac  # usage (README: Exit codes)
mkdir -p "$out/img" "$out/exr" || exit 1
tmp=$(mktemp -d) || exit 1
trap 'rm -rf "$tmp"' EXIT

now() { date +%s.%N; }
# a scene that could not be rendered or compared still gets a row
error_row() {
    total=$((total + 1))
    echo "report: $s: $1" >&2
    echo "<tr><td>$n</td><td></td><td class=\"fail\">ERROR</td><td colspan=\"8\">$(echo "$1" | html)</td></tr>" >> "$rows"
}
# a scene with §3.10 parts (area lights, a thin lens, motion) has no rasterizer counterpart
skip_row() {
    echo "report: $s: skipped ($1)" >&2
    echo "<tr><td>$n</td><td></td><td>SKIP</td><td colspan=\"8\">$(echo "$1" | html)</td></tr>" >> "$rows"
}
secs() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", b - a }'; }
kv() { sed -n "s/^$1=//p" "$tmp/kv"; }
html() { sed 's/&/\&amp;/g; s/</\&lt;/g; s/>/\&gt;/g'; }
fmt() { awk -v v="$1" 'BEGIN { if (v == "inf") print "&infin;"; else printf "%.3g", v }'; }

rows=$tmp/rows; body=$tmp/body; : > "$rows"; : > "$body"
total=0; passed=0; start_all=$(now)
for s in scenes/*.rf scenes/spd/*.nff scenes/spd/*.nff.gz compare/features.rf; do
    [ -f "$s" ] || continue
    n=$(basename "$s"); n=${n%.gz}; n=${n%.nff}; n=${n%.rf}
    case $s in scenes/spd/*) n=spd-$n ;; compare/*) n=compare-$n ;; esac
    # the scene's own aspect ratio at SIZE pixels along the longer side
    res=$("$bin" info "$s" 2>"$tmp/err" | sed -n 's/^image *\([0-9]*\) x \([0-9]*\).*/\1 \2/p')
    if [ -z "$res" ]; then error_row "$(cat "$tmp/err")"; continue; fi
    case " $("$bin" info "$s" 2>/dev/null | sed -n 's/^features *//p') " in
    *" area-lights "* | *" aperture "* | *" motion "*)
        skip_row "distributed ray tracing (§3.10: area lights, thin lens or motion): no OpenGL counterpart to compare with"
        continue ;;
    esac
    set -- $res
    if [ "$1" -ge "$2" ]; then w=$size; h=$(( ($2 * size + $1 / 2) / $1 )); else h=$size; w=$(( ($1 * size + $2 / 2) / $2 )); fi
    [ "$h" -ge 1 ] || h=1; [ "$w" -ge 1 ] || w=1
    echo "report: $s ($w x $h)" >&2
    t0=$(now)
    "$bin" render "$s" --local --quiet --width "$w" --height "$h" -o "$out/exr/$n.tracer.exr" \
        --depth-out "$out/exr/$n.tracer-depth.exr" --png "$out/img/$n.tracer.png" 2>"$tmp/err" || { error_row "tracer: $(cat "$tmp/err")"; continue; }
    t1=$(now)
    "$raster" "$s" --width "$w" --height "$h" -o "$out/exr/$n.raster.exr" \
        --depth-out "$out/exr/$n.raster-depth.exr" --png "$out/img/$n.raster.png" 2>"$tmp/err" || { error_row "rasterizer: $(cat "$tmp/err")"; continue; }
    t2=$(now)
    "$bin" diff "$out/exr/$n.raster.exr" "$out/exr/$n.tracer.exr" --kv \
        --depth-a "$out/exr/$n.raster-depth.exr" --depth-b "$out/exr/$n.tracer-depth.exr" \
        --heatmap "$out/img/$n.heat.png" --depth-heatmap "$out/img/$n.depth.png" > "$tmp/kv"
    rc=$?
    if [ $rc -gt 2 ]; then error_row "refray diff exited with $rc"; continue; fi
    verdict=$(kv verdict); total=$((total + 1)); [ "$verdict" = PASS ] && passed=$((passed + 1))
    px=$(kv all.pixels)
    within=$(awk -v p="$(kv interior.pct_above_255)" 'BEGIN { printf "%.3f", 100 - p }')
    sil=$(awk -v s="$(kv silhouette)" -v p="$px" 'BEGIN { printf "%.1f", 100 * s / p }')
    note=$(sed -n "s/^$n: //p" "$notes" 2>/dev/null | html)
    cls=$(echo "$verdict" | tr 'A-Z' 'a-z')
    cat >> "$rows" <<ROW
<tr><td><a href="#$n">$n</a></td><td>${w}&times;$h</td><td class="$cls">$verdict</td><td>$(fmt "$(kv interior.mean_abs)")</td><td>$within %</td><td>$(fmt "$(kv interior.max_abs)")</td><td>$sil %</td><td>$(kv coverage_mismatch)</td><td>$(fmt "$(kv depth_max_rel)")</td><td>$(fmt "$(kv all.mean_abs)")</td><td>$(secs "$t0" "$t1") / $(secs "$t1" "$t2")</td></tr>
ROW
    metric() { # label, key prefix
        echo "<tr><th>$1</th><td>$(kv "$2.pixels")</td><td>$(fmt "$(kv "$2.max_abs")") at ($(kv "$2.max_x"), $(kv "$2.max_y"))</td><td>$(fmt "$(kv "$2.mean_abs")")</td><td>$(fmt "$(kv "$2.rmse")")</td><td>$(fmt "$(kv "$2.psnr")") dB</td><td>$(fmt "$(kv "$2.rel_mse")")</td><td>$(fmt "$(kv "$2.pct_above_255")") %</td><td>$(fmt "$(kv "$2.pct_above_fail")") %</td></tr>"
    }
    {
        echo "<section id=\"$n\"><h2>$n <span class=\"$cls\">$verdict</span></h2>"
        echo "<p class=\"src\">$(echo "$s" | html), ${w}&times;$h, tracer $(secs "$t0" "$t1") s, rasterizer $(secs "$t1" "$t2") s.
<a href=\"exr/$n.tracer.exr\">tracer EXR</a>, <a href=\"exr/$n.raster.exr\">raster EXR</a>, depth:
<a href=\"exr/$n.tracer-depth.exr\">tracer</a>, <a href=\"exr/$n.raster-depth.exr\">raster</a></p>"
        echo "<div class=\"imgs\">"
        for k in "tracer:refray render --local" "raster:refray-raster (OpenGL, OSMesa or EGL)" "heat:|raster &minus; tracer| (grey: silhouettes)" "depth:depth |&Delta;z|/z (magenta: coverage differs)"; do
            echo "<figure><img src=\"img/$n.${k%%:*}.png\" alt=\"$n ${k%%:*}\"><figcaption>${k#*:}</figcaption></figure>"
        done
        echo "</div><table class=\"m\"><tr><th></th><th>pixels</th><th>max abs</th><th>mean abs</th><th>RMSE</th><th>PSNR</th><th>relMSE</th><th>&gt; 1/255</th><th>&gt; fail</th></tr>"
        metric "all pixels" all
        metric "away from silhouettes" interior
        echo "</table><p>Silhouettes: $(kv silhouette) pixels ($sil %) masked; coverage differs at $(kv coverage_mismatch) pixels; depth away from silhouettes: max relative error $(fmt "$(kv depth_max_rel)"), mean $(fmt "$(kv depth_mean_rel)").</p>"
        [ -n "$note" ] && echo "<p class=\"note\"><b>Remaining differences:</b> $note</p>"
        echo "</section>"
    } >> "$body"
done
elapsed=$(secs "$start_all" "$(now)")
{
    cat <<HEAD
<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>refray cross-validation report</title>
<style>
body { font: 14px/1.4 sans-serif; margin: 1.5em; color: #222; }
table { border-collapse: collapse; margin: 0.5em 0; }
td, th { border: 1px solid #ccc; padding: 2px 8px; text-align: right; }
td:first-child, th:first-child { text-align: left; }
.pass { color: #070; font-weight: bold; } .warn { color: #a60; font-weight: bold; } .fail { color: #b00; font-weight: bold; }
.imgs { display: flex; flex-wrap: wrap; gap: 8px; }
figure { margin: 0; } figure img { display: block; image-rendering: pixelated; border: 1px solid #999; }
figcaption { font-size: 12px; color: #555; }
section { border-top: 2px solid #ddd; margin-top: 1.5em; } .src { color: #555; } .note { background: #ffd; padding: 4px; }
</style></head><body>
<h1>refray cross-validation: tracer (--local) against the OpenGL rasterizer</h1>
<p>$passed of $total scenes pass. Accuracy goal (issue 5), away from silhouettes: mean absolute
difference &le; 1e-4 and &ge; 99.9 % of pixels within 1/255. Each image is the tracer's
<code>refray render --local</code> (primary rays, local Phong, no shadows, reflection or refraction)
and <code>refray-raster</code> (OpenGL 4.5 core through OSMesa or surfaceless EGL, float framebuffer), compared by
<code>refray diff</code> on linear RGB. Silhouettes are the pixels where either depth image is
discontinuous (docs/compare.md); they are reported but not judged. Generated $(date -u '+%Y-%m-%d %H:%M UTC') in $elapsed s.</p>
<p>The full ray-traced images (shadows, mirrors, glass) against Mitsuba 3 and POV-Ray:
<a href="crosscheck/index.html">crosscheck/index.html</a> (made by <code>make crosscheck</code>, docs/crosscheck.md)$([ -f "$out/crosscheck/index.html" ] || echo ' &mdash; not made yet').</p>
<table><tr><th>scene</th><th>size</th><th>verdict</th><th>mean abs</th><th>within 1/255</th><th>max abs</th><th>silhouettes</th><th>coverage &ne;</th><th>depth max rel</th><th>mean abs (all px)</th><th>time tracer / raster (s)</th></tr>
HEAD
    cat "$rows"
    echo "</table><p>Columns judge the pixels away from silhouettes unless marked &ldquo;all px&rdquo;. Heatmaps: log scale, black 0, purple 1e-6 &hellip; white 1.</p>"
    cat "$body"
    echo "</body></html>"
} > "$tmp/index.html" && mv "$tmp/index.html" "$out/index.html" || exit 1
echo "report: $out/index.html: $passed of $total scenes pass ($elapsed s)" >&2
# the report is written either way; the exit status tells CI whether every scene passed
[ "$passed" -eq "$total" ]
