#!/usr/bin/env bash
# `--shard K/N` and `lighthouse merge`: synth (and, with --net, batch predict and eval) in
# two shards give what one run gives, byte for byte but for timings and VDB UUIDs; merging
# an incomplete set, or merging twice, is an error that says so.
#
#   shard_test.sh LIGHTHOUSE WORK_DIR [--net]
set -euo pipefail
exe=$1 work=$2 net=${3:-}
here=$(dirname "$0")
source "$here/same_outputs.sh"
rm -rf "$work" && mkdir -p "$work" && cd "$work"
lh() { "$exe" --threads 1 "$@" </dev/null; }
expect_error() {  # REGEX COMMAND...: exits 1 with one error line matching REGEX
    local re=$1 err rc=0
    shift
    err=$("$@" 2>&1 >/dev/null </dev/null) || rc=$?
    [ $rc = 1 ] || fail "'$*' exited $rc, expected 1"
    echo "$err" | grep -Eq "^lighthouse: error: .*$re" || fail "'$*' said '$err', expected /$re/"
}

tiny=(--seed 5 --count 3 --size 48x36 --envmap-size 32x16 --envmaps 2 --supersample 1 --texel 0.5 --gather 16)
lh synth "${tiny[@]}" -o one 2>/dev/null
lh synth "${tiny[@]}" -o two --shard 1/2 2>/dev/null
[ ! -e two/000000 ] && [ -d two/000001 ] && [ ! -e two/000002 ] || fail "shard 1/2 wrote other examples than 000001"
[ ! -e two/manifest.json ] || fail "a shard wrote manifest.json"
expect_error "incomplete set of shards.*1 of 2 done, missing shard 0" lh merge two
lh synth "${tiny[@]}" -o two --shard 0/2 2>/dev/null
lh merge two 2>/dev/null
expect_error "merged already" lh merge two
same_dataset one two
echo "synth: 2 shards + merge = one run"

if [ "$net" = --net ]; then
    lh predict --examples one -o pred_one 2>/dev/null
    for k in 0 1; do lh predict --examples one -o pred_two --shard $k/2 2>/dev/null; done
    lh merge pred_two 2>/dev/null
    same_file pred_one/predictions.json pred_two/predictions.json
    for v in pred_one/*.vdb; do same_vdb "$v" "pred_two/$(basename "$v")"; done
    [ "$(ls pred_one/*.vdb | wc -l)" = 3 ] || fail "predict --examples wrote $(ls pred_one/*.vdb | wc -l) volumes, not 3"
    echo "predict: 2 shards + merge = one run"

    lh eval --data one --no-oracle -o eval_one >/dev/null 2>&1
    for k in 0 1; do lh eval --data one --no-oracle -o eval_two --shard $k/2 >/dev/null 2>&1; done
    [ ! -e eval_two/table.md ] || fail "an eval shard wrote table.md"
    lh merge eval_two >/dev/null 2>&1
    for f in table.md metrics.csv contact_sheet.png; do same_file eval_one/$f eval_two/$f; done
    expect_error "merged already" lh merge eval_two
    echo "eval: 2 shards + merge = one run"
    # Like predict, eval collapses the fog the camera did not see by default; --no-shell does not.
    grep -q "collapsed into an opaque shell" eval_one/table.md || fail "eval did not shell by default"
    lh eval --data one --no-oracle --no-shell -o eval_fog >/dev/null 2>&1
    ! grep -q "collapsed into an opaque shell" eval_fog/table.md || fail "eval --no-shell shelled"
    echo "eval: the shell by default, the fog with --no-shell"

    # The merged table keeps the note on how "ours" was predicted.
    gain=(--highlight-gain 10 --highlight-knee 1.5)
    lh eval --data one --no-oracle "${gain[@]}" -o gain_one >/dev/null 2>&1
    for k in 0 1; do lh eval --data one --no-oracle "${gain[@]}" -o gain_two --shard $k/2 >/dev/null 2>&1; done
    lh merge gain_two >/dev/null 2>&1
    grep -q 'above luminance 1.5, times 10 (`--highlight-gain`, `--highlight-knee`)' gain_one/table.md ||
        fail "eval --highlight-gain --highlight-knee did not note the gain"
    for f in table.md metrics.csv; do same_file gain_one/$f gain_two/$f; done
    echo "eval --highlight-gain --highlight-knee: 2 shards + merge = one run"
fi
