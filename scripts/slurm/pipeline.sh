#!/usr/bin/env bash
# The whole pipeline as Slurm jobs, each stage waiting for the last (--dependency=afterok):
#
#   synth train split (array of N shards) ┐
#   synth test split  (array of N shards) ┴ merge data sets ─ train ─┬ predict (array) ┐
#                                                                    └ eval    (array) ┴ merge results
#
#   pipeline.sh [OPTIONS] OUT
#
#   --bin PATH           the lighthouse executable (default: build/cli/lighthouse of this checkout)
#   --shards N           tasks per array (default 4)
#   --train-count N      training examples (default 1000; 0: no training split, needs --model)
#   --test-count N       test examples (default 40)
#   --synth-args "..."   more options for both synth runs (sizes, envmaps, --oracle-levels ...)
#   --model FILE         skip training and predict with this model (default: train OUT/model.pt)
#   --train-args "..."   more options for train (--config, --iterations, --batch ...)
#   --train-tasks N      data-parallel ranks for train (srun; default 1)
#   --eval-args "..."    more options for eval (e.g. --no-oracle)
#   --no-eval            predict only
#   --threads N          threads of every predict and eval task (default 0: all the node's
#                        cores); shards reproduce a single run byte for byte only at the same
#                        count, as libtorch's reductions depend on it
#   --sbatch-args "..."  options for every sbatch (--partition, --account, --time ...)
#
# Everything lands in OUT: train/ and test/ (data sets), model.pt, predictions/ (NAME.vdb and
# predictions.json), eval/ (table.md, metrics.csv, contact_sheet.png) and logs/, one log per
# task (JOBNAME-JOBID_TASK.log). OUT must be on a file system every node sees. Running the
# same command again resubmits everything, and each task skips what is done: shards whose
# records exist, merged directories, a finished training (it resumes from its checkpoint).
# Prints the job ids; the last line is the id of the final merge, for `squeue -j` or
# `sbatch --dependency`.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
exe="$here/../../build/cli/lighthouse"
shards=4 train_count=1000 test_count=40 synth_args="" model="" train_args="" train_tasks=1
eval_args="" eval=1 sbatch_args="" threads=0
usage() { sed -n '2,31p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
while [ $# -gt 0 ]; do
    case $1 in
        --bin) exe=$2; shift 2 ;;
        --shards) shards=$2; shift 2 ;;
        --train-count) train_count=$2; shift 2 ;;
        --test-count) test_count=$2; shift 2 ;;
        --synth-args) synth_args=$2; shift 2 ;;
        --model) model=$2; shift 2 ;;
        --train-args) train_args=$2; shift 2 ;;
        --train-tasks) train_tasks=$2; shift 2 ;;
        --eval-args) eval_args=$2; shift 2 ;;
        --no-eval) eval=0; shift ;;
        --sbatch-args) sbatch_args=$2; shift 2 ;;
        --threads) threads=$2; shift 2 ;;
        -h | --help) usage ;;
        -*) echo "pipeline.sh: unknown option '$1'" >&2; usage ;;
        *) break ;;
    esac
done
[ $# -eq 1 ] || usage
for v in "$shards" "$train_count" "$test_count" "$train_tasks" "$threads"; do
    [[ $v =~ ^[0-9]+$ ]] || { echo "pipeline.sh: '$v' is not a count" >&2; exit 2; }
done
[ "$shards" -ge 1 ] && [ "$test_count" -ge 1 ] && [ "$train_tasks" -ge 1 ] ||
    { echo "pipeline.sh: --shards, --test-count and --train-tasks must be at least 1" >&2; exit 2; }
[ "$train_count" -ge 1 ] || [ -n "$model" ] || { echo "pipeline.sh: --train-count 0 needs --model" >&2; exit 2; }
[ -x "$exe" ] || { echo "pipeline.sh: '$exe' is not executable (build first, or give --bin)" >&2; exit 2; }
command -v sbatch >/dev/null || { echo "pipeline.sh: sbatch not found (is this a Slurm submit host?)" >&2; exit 2; }
mkdir -p "$1/logs"
out=$(cd "$1" && pwd)
exe=$(cd "$(dirname "$exe")" && pwd)/$(basename "$exe")
[ -z "$model" ] || model=$(cd "$(dirname "$model")" && pwd)/$(basename "$model")

# submit NAME [sbatch options] SCRIPT ARGS...: prints the job id. Logs: one per task,
# JOBNAME-JOBID_TASK.log for arrays, JOBNAME-JOBID.log otherwise.
submit() {
    local name=$1 log="%x-%j.log"
    shift
    case " $* " in *" --array="*) log="%x-%A_%a.log" ;; esac
    # shellcheck disable=SC2086
    sbatch --parsable --job-name="lh-$name" --output="$out/logs/$log" $sbatch_args "$@" | cut -d';' -f1
}
array="--array=0-$((shards - 1))"
# shellcheck disable=SC2086
synth() {  # SPLIT COUNT
    submit "synth-$1" $array "$here/shard_task.sh" "$shards" "$out/$1" \
        "$exe" --threads 1 synth --split "$1" --count "$2" $synth_args -o "$out/$1"
}

data_jobs=()
if [ "$train_count" -ge 1 ]; then
    data_jobs+=("$(synth train "$train_count")")
    echo "synth train: job ${data_jobs[-1]} ($shards tasks)"
fi
data_jobs+=("$(synth test "$test_count")")
echo "synth test: job ${data_jobs[-1]} ($shards tasks)"
dirs=("$out/test")
[ "$train_count" -lt 1 ] || dirs=("$out/train" "$out/test")
merge_data=$(submit merge-data --dependency=afterok:$(IFS=:; echo "${data_jobs[*]}") \
    "$here/merge_task.sh" "$exe" "${dirs[@]}")
echo "merge data sets: job $merge_data"

after=$merge_data
if [ -z "$model" ]; then
    model=$out/model.pt
    # shellcheck disable=SC2086
    train=$(submit train --dependency=afterok:$merge_data --ntasks="$train_tasks" \
        "$here/train_task.sh" "$exe" train --data "$out/train" $train_args -o "$model")
    echo "train: job $train ($train_tasks ranks)"
    after=$train
fi

result_jobs=()
result_dirs=("$out/predictions")
result_jobs+=("$(submit predict --dependency=afterok:$after $array "$here/shard_task.sh" "$shards" \
    "$out/predictions" "$exe" --threads "$threads" predict --examples "$out/test" --model "$model" -o "$out/predictions")")
echo "predict: job ${result_jobs[-1]} ($shards tasks)"
if [ "$eval" = 1 ]; then
    # shellcheck disable=SC2086
    result_jobs+=("$(submit eval --dependency=afterok:$after $array "$here/shard_task.sh" "$shards" \
        "$out/eval" "$exe" --threads "$threads" eval --data "$out/test" --model "$model" $eval_args -o "$out/eval")")
    echo "eval: job ${result_jobs[-1]} ($shards tasks)"
    result_dirs+=("$out/eval")
fi
merge_results=$(submit merge-results --dependency=afterok:$(IFS=:; echo "${result_jobs[*]}") \
    "$here/merge_task.sh" "$exe" "${result_dirs[@]}")
echo "merge results: job $merge_results"
echo "$merge_results"
