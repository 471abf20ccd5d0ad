#!/usr/bin/env bash
# scripts/slurm/ on a real one-node Slurm: starts munged, slurmctld and slurmd from Debian's
# packages (scripts/slurm/one_node_cluster.sh, everything under a temporary directory), runs
# the whole pipeline: 4-task synth arrays of a training and a test split, their merge,
# data-parallel training with 2 ranks started by srun (a few iterations of the `small`
# configuration), a 4-task predict array, a 4-task eval array and their merges; checks that the
# data sets, the model file, the volumes and Table 2 are those of the single-process commands
# (one `train` process with the whole batch); then runs the pipeline again and checks that
# every task skipped its finished work. The daemons are stopped on every exit.
#
#   slurm_pipeline_test.sh LIGHTHOUSE SOURCE_DIR
#
# Exits 77 (ctest: skipped) when not root or when Slurm or MUNGE is not installed.
set -euo pipefail
exe=$1 src=$2
if [ "$(id -u)" -ne 0 ]; then echo "skipped: needs root (slurmd)"; exit 77; fi
for tool in munged slurmctld slurmd sbatch squeue; do
    command -v "$tool" >/dev/null || { echo "skipped: $tool not installed (apt-get install slurm-wlm munge)"; exit 77; }
done
source "$src/tests/shard/same_outputs.sh"
tmp=$(mktemp -d /tmp/lighthouse_slurm_test.XXXXXX)
cleanup() {
    "$src/scripts/slurm/one_node_cluster.sh" stop "$tmp/cluster" || true
    rm -rf "$tmp"
}
trap cleanup EXIT
trap "exit 1" TERM INT
"$src/scripts/slurm/one_node_cluster.sh" start "$tmp/cluster"
export SLURM_CONF=$tmp/cluster/slurm.conf

tiny="--size 48x36 --envmap-size 32x16 --envmaps 1 --supersample 1 --texel 0.5 --gather 16"
# Waits until job $1 has left the queue (or $2 seconds); fails with the logs otherwise.
wait_job() {
    local job=$1 limit=$2 t=0
    while [ -n "$(squeue -h -j "$job" 2>/dev/null)" ]; do
        sleep 1
        t=$((t + 1))
        if [ $t -ge "$limit" ]; then
            squeue >&2 || true
            tail -n 5 "$tmp"/out/logs/*.log >&2 || true
            fail "job $job still queued after $limit s"
        fi
    done
}
# Two ranks of one example each against one process with the batch of 2 (net/distributed.h).
train_args="--config small --iterations 3 --batch 2 --validate-every 3 --validation-scenes 1 --log-every 1 --threads 1"
run_pipeline() {
    bash "$src/scripts/slurm/pipeline.sh" --bin "$exe" --shards 4 --train-count 4 --test-count 4 \
        --train-tasks 2 --train-args "$train_args" --threads 1 \
        --synth-args "$tiny" --eval-args "--no-oracle" "$tmp/out" | tee "$tmp/jobs.txt"
}

t0=$(date +%s)
run_pipeline
wait_job "$(tail -n 1 "$tmp/jobs.txt")" 240
[ -f "$tmp/out/eval/table.md" ] || { tail -n 20 "$tmp"/out/logs/*.log >&2; fail "the pipeline wrote no table.md"; }
echo "pipeline: $(( $(date +%s) - t0 )) s"
[ "$(ls "$tmp"/out/logs/lh-synth-test-*.log | wc -l)" = 4 ] || fail "expected one log per synth task"

grep -q "rank 1 of 2 joined" "$tmp"/out/logs/lh-train-*.log || fail "training did not run as 2 ranks"

# The same work in one process each.
"$exe" --threads 1 synth --split train --count 4 $tiny -o "$tmp/one/train" 2>/dev/null
"$exe" --threads 1 synth --split test --count 4 $tiny -o "$tmp/one/test" 2>/dev/null
# shellcheck disable=SC2086
"$exe" train --data "$tmp/one/train" $train_args -o "$tmp/one/model.pt" >/dev/null 2>&1
"$exe" --threads 1 predict --examples "$tmp/one/test" --model "$tmp/one/model.pt" -o "$tmp/one/predictions" 2>/dev/null
"$exe" --threads 1 eval --data "$tmp/one/test" --model "$tmp/one/model.pt" --no-oracle -o "$tmp/one/eval" >/dev/null 2>&1
same_dataset "$tmp/one/train" "$tmp/out/train"
same_dataset "$tmp/one/test" "$tmp/out/test"
same_file "$tmp/one/model.pt" "$tmp/out/model.pt"
echo "model trained by 2 srun ranks = model trained by one process"
for v in "$tmp"/one/predictions/*.vdb; do same_vdb "$v" "$tmp/out/predictions/$(basename "$v")"; done
# predictions.json and table.md name the paths of the data set and the model, which differ:
# compare them with those swapped.
diff <(sed "s|$tmp/one/|X/|g" "$tmp/one/predictions/predictions.json") \
     <(sed "s|$tmp/out/|X/|g" "$tmp/out/predictions/predictions.json") >&2 || fail "predictions.json differ"
for f in metrics.csv contact_sheet.png; do same_file "$tmp/one/eval/$f" "$tmp/out/eval/$f"; done
diff <(sed "s|$tmp/one/|X/|g" "$tmp/one/eval/table.md") <(sed "s|$tmp/out/|X/|g" "$tmp/out/eval/table.md") >&2 ||
    fail "table.md differ"
echo "slurm pipeline = single-process commands"

# A re-run resubmits everything; every task finds its work done.
t0=$(date +%s)
run_pipeline
wait_job "$(tail -n 1 "$tmp/jobs.txt")" 120
grep -l "done already" "$tmp"/out/logs/lh-synth-test-*.log | wc -l | grep -qx 4 || fail "synth tasks of the re-run did not skip"
grep -q "merged already" "$tmp"/out/logs/lh-merge-results-*.log || fail "the re-run merged again"
echo "re-run: skipped finished work in $(( $(date +%s) - t0 )) s"
