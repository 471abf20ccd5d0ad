#!/usr/bin/env bash
# scripts/paired_timing.sh on two runs of one benchmark binary: one line per pair whose ratio
# is B / A of its own times, and a summary whose median and quartiles are those of the printed
# ratios. Checks the arithmetic, not the times (they are whatever the machine gives).
#   paired_timing_test.sh BENCH_BINARY ROUNDS
set -euo pipefail
bench=$1 rounds=$2
script="$(dirname "$0")/../../scripts/paired_timing.sh"
fail() { echo "FAIL: $*" >&2; exit 1; }

out=$(bash "$script" "$bench" "$bench" "$rounds") || fail "paired_timing.sh exited non-zero"
echo "$out"
pairs=$((2 * rounds))
[ "$(grep -c '^A [0-9.e+]*  B [0-9.e+]*  B/A [0-9.]*$' <<< "$out")" = "$pairs" ] ||
  fail "expected $pairs pair lines"
# Each pair's ratio is its B over its A (to the 4 printed decimals).
awk '/^A / { if ($2 <= 0 || $4 <= 0) exit 1; d = $4 / $2 - $6; if (d > 1e-4 || d < -1e-4) exit 1 }' \
  <<< "$out" || fail "a pair's B/A is not its B over its A"
# The summary: the median, and as quartiles the k-th smallest and k-th largest ratio,
# k = floor(N/4) + 1.
expected=$(awk '/^A / { print $6 }' <<< "$out" | /usr/bin/python3 -c '
import statistics, sys
r = sorted(float(x) for x in sys.stdin.read().split())
n = len(r)
print("B/A over %d pairs: median %.3f, quartiles %.3f and %.3f" % (
    n, statistics.median(r), r[n // 4], r[-(n // 4) - 1]))')
summary=$(tail -n 1 <<< "$out")
[ "$summary" = "$expected" ] || fail "summary '$summary', expected '$expected'"
echo "paired_timing_test: ok"
