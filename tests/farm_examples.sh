#!/bin/sh
# Runs the examples of examples/farm/ for tests/test_farm.c (t_farm_examples), which then
# compares the images bit for bit. usage: tests/farm_examples.sh /abs/path/to/refray TMPDIR
set -eu
bin=$1 dir=$2
opts="--width 96 --height 72 --samples 2 --threads 1"
export REFRAY="$bin"

# the single renders everything is compared with
"$bin" render scenes/whitted.rf -o "$dir/ref.exr" $opts --quiet
"$bin" render scenes/whitted.rf -o "$dir/ref_whitted.exr" $opts --quiet
"$bin" render scenes/spd/tetra.nff -o "$dir/ref_tetra.exr" $opts --quiet

# GNU parallel: 4 tiles on two local job slots, merged; a batch of two scenes
sh examples/farm/parallel-tiles.sh scenes/whitted.rf "$dir/parallel.exr" 4 2/: -- $opts
[ ! -e "$dir/parallel.exr.tiles" ] || { echo "parallel-tiles.sh left its tiles"; exit 1; }
printf 'scenes/whitted.rf\nscenes/spd/tetra.nff\n' > "$dir/list"
sh examples/farm/parallel-batch.sh "$dir/list" "$dir/pbatch" 2/: -- $opts
[ -s "$dir/pbatch/whitted.png" ] && [ -s "$dir/pbatch/tetra.png" ] || { echo "parallel-batch.sh wrote no PNGs"; exit 1; }

# Slurm, as Slurm runs the job scripts: one process per array index, then the merge; a batch
for k in 0 1 2 3; do
    SLURM_ARRAY_TASK_ID=$k SLURM_CPUS_PER_TASK=1 bash examples/farm/slurm-tiles.sbatch scenes/whitted.rf 4 "$dir/sl" $opts
done
bash examples/farm/slurm-merge.sbatch "$dir/sl" "$dir/slurm.exr"
[ -s "$dir/slurm.png" ] || { echo "slurm-merge.sbatch wrote no PNG"; exit 1; }
for k in 0 1; do
    SLURM_ARRAY_TASK_ID=$k bash examples/farm/slurm-batch.sbatch "$dir/list" "$dir/sbatch" $opts
done

# Slurm's own parser, where Slurm is installed: with a cluster configuration but no controller,
# sbatch --test-only reads every #SBATCH line and option, then fails only to reach the controller
if command -v sbatch >/dev/null 2>&1; then
    printf 'ClusterName=refray\nSlurmctldHost=localhost\nMessageTimeout=1\nTCPTimeout=1\nNodeName=localhost CPUs=2 State=UNKNOWN\nPartitionName=debug Nodes=localhost Default=YES MaxTime=INFINITE State=UP\n' > "$dir/slurm.conf"
    for f in slurm-tiles.sbatch slurm-merge.sbatch slurm-batch.sbatch; do
        out=$(SLURM_CONF="$dir/slurm.conf" timeout 60 sbatch --test-only --array=0-3 --dependency=afterok:1 \
            "examples/farm/$f" a b c 2>&1 || true)
        case $out in
        *"Unable to contact slurm controller"*) echo "sbatch --test-only $f: parsed" ;;
        *) echo "sbatch --test-only $f: $out"; exit 1 ;;
        esac
    done
else
    echo "(sbatch is not installed: the Slurm scripts ran as plain scripts only; apt-get install slurm-client)"
fi
