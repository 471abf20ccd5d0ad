#!/usr/bin/env bash
# One task of a Slurm job array: shard K of N of a batch command, K = SLURM_ARRAY_TASK_ID.
# A shard whose record (RECORD_DIR/shard-K-of-N.json) exists is done: the task says so and
# exits 0, so a re-run of the whole pipeline only redoes what did not finish.
#
#   sbatch --array=0-$((N - 1)) shard_task.sh N RECORD_DIR LIGHTHOUSE COMMAND ARGS...
#
# RECORD_DIR is where the command writes (synth -o, predict -o, eval -o). N is given
# rather than read from SLURM_ARRAY_TASK_COUNT so that a re-submission of some indices only
# (--array=1,3) still shards by the full count.
set -euo pipefail
[ $# -ge 4 ] || { sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
n=$1 record_dir=$2
shift 2
k=${SLURM_ARRAY_TASK_ID:?shard_task.sh runs as a task of a Slurm job array (sbatch --array)}
record="$record_dir/shard-$k-of-$n.json"
if [ -f "$record" ]; then
    echo "shard $k of $n: done already ($record)"
    exit 0
fi
echo "shard $k of $n on $(hostname -s): $* --shard $k/$n"
exec "$@" --shard "$k/$n"
