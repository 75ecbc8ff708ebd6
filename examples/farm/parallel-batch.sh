#!/bin/sh
# A batch of scenes (one path per line of LIST, e.g. every scene of every exercise sheet) as one
# GNU parallel job list over several hosts: OUTDIR/NAME.exr and OUTDIR/NAME.png per scene.
#
# usage: examples/farm/parallel-batch.sh LIST OUTDIR [HOSTS] [-- RENDER OPTIONS...]
#   HOSTS  as in parallel-tiles.sh (default "2/:": two jobs on this machine)
# A scene that fails stops nothing else; the script's exit code is the number of failed scenes
# (GNU parallel's), and the log names them.
set -eu
[ $# -ge 2 ] || { sed -n '5,8p' "$0" >&2; exit 5; }  # usage (README: Exit codes)
list=$1 outdir=$2
shift 2
hosts="2/:"
if [ $# -gt 0 ] && [ "$1" != "--" ]; then hosts=$1; shift; fi
[ $# -gt 0 ] && [ "$1" = "--" ] && shift
refray=${REFRAY:-refray}
mkdir -p "$outdir"
# {/.}: the scene's file name without folder and extension
parallel -q -S "$hosts" --joblog "$outdir/batch.log" \
    "$refray" render {} -o "$outdir/{/.}.exr" --png "$outdir/{/.}.png" --quiet "$@" :::: "$list"
