#!/bin/sh
# One image rendered as N tiles by GNU parallel (Debian package `parallel`) on several hosts,
# then merged; the result is bit for bit the single render's (refray's random numbers are keyed
# by pixel, not by process).
#
# usage: examples/farm/parallel-tiles.sh SCENE OUT.exr N [HOSTS] [-- RENDER OPTIONS...]
#   N      tiles (refray render --tiles N --tile K, K = 0 .. N-1)
#   HOSTS  GNU parallel's --sshlogin list: "2/:" two jobs on this machine (the default),
#          "4/node1,4/node2,2/:" four jobs on each of two hosts by ssh and two here. Every host
#          needs refray on its PATH (or set REFRAY) and the scene, the output folder and this
#          folder at the same paths: a shared filesystem, as on a cluster.
#   RENDER OPTIONS  passed to every tile: --samples, --width, --threads (per job), ...
# The tiles go to OUT.exr.tiles/ and are removed after a successful merge.
set -eu
[ $# -ge 3 ] || { sed -n '5,14p' "$0" >&2; exit 5; }  # usage (README: Exit codes)
scene=$1 out=$2 n=$3
shift 3
hosts="2/:"
if [ $# -gt 0 ] && [ "$1" != "--" ]; then hosts=$1; shift; fi
[ $# -gt 0 ] && [ "$1" = "--" ] && shift
refray=${REFRAY:-refray}
dir="$out.tiles"
mkdir -p "$dir"
# -q: the arguments reach refray as they are (no second round of shell parsing); --halt: the
# first failing tile stops the rest and fails the script
seq 0 $((n - 1)) | parallel -q --halt now,fail=1 -S "$hosts" \
    "$refray" render "$scene" --tiles "$n" --tile {} -o "$dir/tile_{}.exr" --quiet "$@"
"$refray" merge "$dir"/tile_*.exr -o "$out"
rm -rf "$dir"
