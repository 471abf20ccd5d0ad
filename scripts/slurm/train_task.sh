#!/usr/bin/env bash
# The training job of the pipeline. With one task, `lighthouse train` runs here; with
# several (sbatch --ntasks=N, on one node or many), srun starts N ranks of data-parallel
# training (docs/distributed.md): each reads its rank and the world size from srun's
# SLURM_PROCID and SLURM_STEP_NUM_TASKS, and meets the others at MASTER_ADDR:MASTER_PORT,
# by default the allocation's first node and a port drawn from the job id.
#
#   sbatch [--ntasks=N] train_task.sh LIGHTHOUSE train ARGS...
set -euo pipefail
[ $# -ge 2 ] || { sed -n '2,9p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
tasks=${SLURM_NTASKS:-1}
if [ "$tasks" -gt 1 ]; then
    export MASTER_ADDR=${MASTER_ADDR:-$(scontrol show hostnames "$SLURM_JOB_NODELIST" | head -n 1)}
    export MASTER_PORT=${MASTER_PORT:-$((20000 + ${SLURM_JOB_ID:-0} % 20000))}
    echo "train: $tasks ranks, rendezvous at $MASTER_ADDR:$MASTER_PORT"
    exec srun --kill-on-bad-exit=1 "$@"
fi
exec "$@"
