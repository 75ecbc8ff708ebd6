#!/bin/sh
# `make demo`: a short tour of `refray formula` (the tracer's demo replaces it once it exists).
set -e
bin=${1:-build/refray}
run() { echo "\$ refray formula $*"; "$bin" formula "$@"; echo; }
run cross a=1,0,0 b=0,1,0
run barycentric p1=0,0 p2=4,0 p3=0,4 q=1,1
run euler psi_deg=30 theta_deg=45 phi_deg=60 order=zyx
run axis-angle d=1,1,1 phi_deg=120 point=1,0,0
run inverse matrix='2,0,0;0,4,0;0,0,8' kind=scale
run transform-normal matrix='2,0,0;0,1,0;0,0,1' n=1,1,0
echo "refray formula list   # every id; refray formula ID --help for its inputs"
