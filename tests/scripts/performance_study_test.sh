#!/usr/bin/env bash
# scripts/performance_study.sh --quick: every volume's speed and memory runs happen and the
# summary reads the targets from them (the quick run's 60x30 envmaps are not judged against
# the 240x120 speed targets); a wrong argument is one error line and exit 2.
#   performance_study_test.sh LIGHTHOUSE_BINARY SCRATCH_DIR
set -euo pipefail
bin=$1 scratch=$2
script="$(dirname "$0")/../../scripts/performance_study.sh"
rm -rf "$scratch"
fail() { echo "FAIL: $*" >&2; exit 1; }

LIGHTHOUSE=$bin bash "$script" --quick "$scratch" > "$scratch.stdout" 2> "$scratch.stderr" ||
  { cat "$scratch.stderr" >&2; fail "the quick study exited non-zero"; }
summary=$scratch/summary.md
[ -s "$summary" ] || fail "no $summary"
cmp -s "$summary" "$scratch.stdout" || fail "the summary printed is not the one written"
volumes=(oracle example)
"$bin" predict --help > /dev/null 2>&1 && volumes+=(predicted)
for v in "${volumes[@]}"; do
  for f in speed/speed_error.csv speed/speed_error.md speed/speed_error.svg memory/memory_error.csv \
           memory/memory_error.md memory/memory_error.svg memory/memory_breakdown.md; do
    [ -s "$scratch/$v/$f" ] || fail "no $v/$f"
  done
  grep -q "^# $v (" "$summary" || fail "no section for $v"
  grep -q "(\(.*/\)\{0,1\}$v/speed/speed_error.svg)" "$summary" || fail "no speed plot of $v in the summary"
done
# The plots are well-formed XML (browsers draw nothing of an SVG that is not).
/usr/bin/python3 -c 'import sys, xml.etree.ElementTree as E; [E.parse(f) for f in sys.argv[1:]]' \
  "$scratch"/*/speed/speed_error.svg "$scratch"/*/memory/memory_error.svg || fail "a plot is not well-formed XML"
# Each volume: the speed targets (not judged at 60x30) and the storage target (judged).
[ "$(grep -c '^\* not judged: this run rendered 60x30 envmaps' "$summary")" = "${#volumes[@]}" ] ||
  fail "the speed targets are not reported (as not judged) for every volume"
[ "$(grep -c '^\* on disk (Blosc, half precision): .* of dense: \*\*\(not \)\{0,1\}met\*\*' "$summary")" = "${#volumes[@]}" ] ||
  fail "the storage target is not judged for every volume"
# Ground truth exists for the oracle (and the predicted volume): its loss is judged.
grep -q 'PSNR against ground truth [0-9.]* dB, [-0-9.]* dB lost: \*\*' "$summary" || fail "no loss against ground truth"
grep -q 'quick run' "$summary" || fail "the quick run is not marked as such"

# Bad arguments.
if LIGHTHOUSE=$bin bash "$script" --no-such-option 2> "$scratch.err"; then fail "an unknown option was accepted"; fi
[ "$(wc -l < "$scratch.err")" = 1 ] && grep -q "unknown option '--no-such-option'" "$scratch.err" ||
  fail "unknown option: $(cat "$scratch.err")"
if LIGHTHOUSE=$bin bash "$script" --quick --docs "$scratch/y" 2> "$scratch.err"; then fail "--quick --docs was accepted"; fi
grep -q "docs keeps full runs only" "$scratch.err" || fail "--quick --docs: $(cat "$scratch.err")"
if LIGHTHOUSE=/no/such/lighthouse bash "$script" --quick "$scratch/x" 2> "$scratch.err"; then fail "a missing binary was accepted"; fi
grep -q "/no/such/lighthouse not found" "$scratch.err" || fail "missing binary: $(cat "$scratch.err")"
[ ! -e "$scratch/x" ] || fail "a failed start left an output directory"
echo "performance study (quick): ${volumes[*]}: ok"
