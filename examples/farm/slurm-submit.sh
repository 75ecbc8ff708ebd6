#!/bin/sh
# Submits one image as N tiles (a job array, slurm-tiles.sbatch) and the merge that waits for
# all of them (slurm-merge.sbatch, --dependency=afterok).
#
# usage: examples/farm/slurm-submit.sh SCENE OUT.exr N [RENDER OPTIONS...]
set -eu
[ $# -ge 3 ] || { sed -n '5p' "$0" >&2; exit 5; }  # usage (README: Exit codes)
here=$(dirname "$0")
scene=$1 out=$2 n=$3
shift 3
dir="$out.tiles"
jid=$(sbatch --parsable --array=0-$((n - 1)) "$here/slurm-tiles.sbatch" "$scene" "$n" "$dir" "$@")
sbatch --parsable --dependency=afterok:"${jid%%;*}" "$here/slurm-merge.sbatch" "$dir" "$out"
