#!/bin/sh
# Drives refray-view through real X events (xdotool on Xvfb), for tests/test_view.c: keys, a
# click, a drag, a broken and a repaired edit of the scene file, saving, quitting. Run under
# xvfb-run. usage: tests/view_interactive.sh /abs/refray-view /abs/refray /abs/refray-raster DIR
set -u
view=$1 bin=$2 raster=$3 dir=$4
cp scenes/whitted.rf "$dir/scene.rf"
cd "$dir"
fail() { echo "FAIL: $*"; echo "--- stdout"; cat view.out; echo "--- stderr"; cat view.err; kill "$pid" 2>/dev/null; exit 1; }
# title PATTERN: wait (30 s at most) until the window's title (the status line) matches
title() {
    i=0
    while [ $i -lt 300 ]; do
        t=$(xdotool getwindowname "$wid" 2>/dev/null)
        case $t in *$1*) return 0 ;; esac
        sleep 0.1
        i=$((i + 1))
    done
    fail "the title never showed '$1' (it says: $t)"
}
key() { xdotool windowfocus --sync "$wid" 2>/dev/null; xdotool key "$1"; }

"$bin" render scene.rf --width 160 --height 120 --samples 2 -o ref.exr --quiet || exit 1
"$raster" scene.rf --width 160 --height 120 -o ref_gl.exr --png ref_gl.png || exit 1
"$view" scene.rf --width 160 --height 120 --samples 2 > view.out 2> view.err &
pid=$!
wid=$(timeout 20 xdotool search --sync --onlyvisible --name "refray-view" | head -1)
[ -n "$wid" ] || fail "no window"
title "| 2/2 spp"
key s                                   # 1: the converged tracer image
i=0; while [ ! -f view-1.exr ] && [ $i -lt 50 ]; do sleep 0.1; i=$((i + 1)); done
"$bin" diff view-1.exr ref.exr --kv | grep -q '^all.max_abs=0$' || fail "the converged image is not refray render's"
key g; title "OpenGL raster"; key s     # 2: the rasterization
i=0; while [ ! -f view-2.png ] && [ $i -lt 50 ]; do sleep 0.1; i=$((i + 1)); done
"$bin" diff view-2.exr ref_gl.exr --kv | grep -q '^all.max_abs=0$' || fail "the OpenGL view is not refray-raster's image"
key t; title "| tracer"
key c; sleep 0.3
grep -q "^camera eye 0 2.6 7  target 0 0.6 0  up 0 1 0  fov 40" view.out || fail "C did not print the camera"
xdotool mousemove --window "$wid" 50 70 click 1; title "| pixel (50, 70)"
grep -q "^pixel (50, 70): linear RGB .*; hits " view.out || fail "the inspector did not name the primitive"
cp scene.rf good.rf
printf 'sphere 0 0 0 -1\n' >> scene.rf; touch scene.rf
title "ERROR: scene.rf:"                # a broken edit: its position, the window stays
cp good.rf scene.rf; touch scene.rf
i=0; while [ $i -lt 100 ]; do case $(xdotool getwindowname "$wid") in *ERROR*) sleep 0.1 ;; *) break ;; esac; i=$((i + 1)); done
title "| 2/2 spp"
xdotool mousemove --window "$wid" 80 60 mousedown 1 mousemove --window "$wid" 110 60 mouseup 1
sleep 0.3; title "| 2/2 spp"; key s     # 3: orbited
i=0; while [ ! -f view-3.exr ] && [ $i -lt 50 ]; do sleep 0.1; i=$((i + 1)); done
key r; sleep 0.3; title "| 2/2 spp"; key s  # 4: reset: the first image again
i=0; while [ ! -f view-4.exr ] && [ $i -lt 50 ]; do sleep 0.1; i=$((i + 1)); done
"$bin" diff view-4.exr ref.exr --kv | grep -q '^all.max_abs=0$' || fail "R did not reset the camera"
key Left; key Page_Up; sleep 0.3; title "| 2/2 spp"; key s  # 5: arrow and page keys move the camera
i=0; while [ ! -f view-5.exr ] && [ $i -lt 50 ]; do sleep 0.1; i=$((i + 1)); done
"$bin" diff view-3.exr ref.exr --kv | grep -q '^all.max_abs=0$' && fail "the drag did not move the camera"
"$bin" diff view-5.exr ref.exr --kv | grep -q '^all.max_abs=0$' && fail "the arrow and page keys did not move the camera"
key q
i=0; while kill -0 "$pid" 2>/dev/null && [ $i -lt 100 ]; do sleep 0.1; i=$((i + 1)); done
kill -0 "$pid" 2>/dev/null && fail "Q did not quit"
wait "$pid" || fail "exit status $?"
echo "interactive: keys, click, drag, reload, save and quit all work"
