#!/usr/bin/env bash
# Compares the speed of two builds of a Google Benchmark executable on this noisy VM: the two
# run at the same time, one per core and single-threaded, then swapped, so that both see the
# same machine; the ratio of a pair (B / A) is stable where the times are not. Prints every
# pair and the median and quartiles of the ratios.
#
#   scripts/paired_timing.sh OLD_BENCH NEW_BENCH [ROUNDS]     (2 pairs per round; default 8)
#
# Environment: FILTER (benchmark filter, default 'File/2/'), MIN_TIME (seconds per run,
# default 0.5), LIGHTHOUSE_BENCH_VOLUME (default: the oracle of scripts/oracle_ceiling.sh).
set -euo pipefail
if [ $# -lt 2 ] || [ ! -x "$1" ] || [ ! -x "$2" ]; then
  echo "usage: $0 OLD_BENCH NEW_BENCH [ROUNDS] (two executable benchmark binaries)" >&2
  exit 2
fi
if [ "$(nproc)" -lt 2 ]; then echo "$0: needs two cores (one per binary), this machine has $(nproc)" >&2; exit 2; fi
a=$1 b=$2 rounds=${3:-8}
filter=${FILTER:-File/2/} minTime=${MIN_TIME:-0.5}
export LIGHTHOUSE_BENCH_VOLUME=${LIGHTHOUSE_BENCH_VOLUME:-out/oracle_ceiling/oracle_5x64/000001.vdb}
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
# Time of the first benchmark matching the filter, run single-threaded on one core.
timeOn() {  # cpu binary output
  taskset -c "$1" "$2" --benchmark_filter="$filter" --benchmark_min_time="$minTime" 2>/dev/null |
    awk '/^BM/ { print $2; exit }' > "$3"
}
for round in $(seq "$rounds"); do
  for cpus in "0 1" "1 0"; do
    set -- $cpus
    timeOn "$1" "$a" "$scratch/a" & timeOn "$2" "$b" "$scratch/b" & wait
    ta=$(cat "$scratch/a") tb=$(cat "$scratch/b")
    if [ -z "$ta" ] || [ -z "$tb" ]; then echo "$0: no time from a benchmark run (filter '$filter' matched nothing, or the binary failed)" >&2; exit 1; fi
    echo "$ta $tb" | awk '{ printf "A %s  B %s  B/A %.4f\n", $1, $2, $2 / $1 }' | tee -a "$scratch/pairs"
  done
done
# Quartiles: the k-th smallest and the k-th largest ratio, k = floor(N/4) + 1.
awk '{ print $6 }' "$scratch/pairs" | sort -n | awk '{ r[NR] = $1 } END {
  printf "B/A over %d pairs: median %.3f, quartiles %.3f and %.3f\n", NR, (r[int((NR + 1) / 2)] + r[int(NR / 2) + 1]) / 2,
         r[int(NR / 4) + 1], r[NR - int(NR / 4)] }'
