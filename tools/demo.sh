#!/bin/sh
# `make demo`: renders the default scene (scenes/whitted.rf, the classic Whitted scene of
# docs/bench-scenes.md) to out/whitted.exr (linear) and out/whitted.png (gamma 2.2), then shows a few
# formula calls.
set -e
bin=${1:-build/refray}
mkdir -p out
echo "\$ refray render scenes/whitted.rf -o out/whitted.exr --png out/whitted.png"
"$bin" render scenes/whitted.rf -o out/whitted.exr --png out/whitted.png
echo "wrote out/whitted.exr and out/whitted.png"
echo
run() { echo "\$ refray formula $*"; "$bin" formula "$@"; echo; }
run intersect-sphere origin=0,0,5 dir=0,0,-1 center=0,0,0 radius=1
run fresnel eta_i=1 eta_t=1.5 cos_i=1
run barycentric p1=0,0 p2=4,0 p3=0,4 q=1,1
echo "more: refray formula list; refray info scenes/whitted.rf; refray chromaticity -o diagram.png"
