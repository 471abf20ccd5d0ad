#!/usr/bin/env bash
# The command grammar (docs/cli.md) in the network's commands, which `lighthouse` hands to
# `lighthouse-net`:
#   - --threads before or after the command word reaches libtorch ("N threads" in train's log);
#   - train writes -o OUT in float32 unless --half (half the size); --out and --float-model
#     still work, with one deprecation warning each;
#   - predict renders envmaps at --at and --points FILE as EXR, with a PNG beside them only
#     with --png; the old --envmap-at still works, warns, and still writes both.
#   grammar_net_test.sh LIGHTHOUSE WORKDIR PAIR_DIR
# PAIR_DIR is data/demo_pair, or "" where there is no bundled model (predict is then skipped).
set -u
[ $# -eq 3 ] || { echo "usage: $0 LIGHTHOUSE WORKDIR PAIR_DIR" >&2; exit 2; }
lh=$1
work=$2
pair=$3
source "$(dirname "$0")/harness.sh"
fresh_workdir "$work"
run() {
    local name=$1
    shift
    "$lh" "$@" </dev/null >"$name.out" 2>"$name.err" || { fail "$name: exit $?: $(cat "$name.err")"; return 1; }
}
warnings() { grep -c "is deprecated" "$1.err"; }

"$lh" synth --seed 3 --count 2 --size 48x36 --envmap-size 32x16 --envmaps 1 --supersample 1 -o syn \
    </dev/null >/dev/null 2>&1 || { echo "synth failed"; exit 1; }
# One iteration of the small network: a few seconds.
train=(--data syn --config small --iterations 1 --validate-every 1 --validation-scenes 1 --no-resume)

# 3 threads is neither libtorch's default here nor anywhere it would be by chance.
run train_old train --threads 3 "${train[@]}" --float-model --out old.pt &&
    grep -q "3 threads on cpu" train_old.err || fail "train --threads 3 (after the command): $(cat train_old.err)"
[ "$(grep -c '^warning: --out is deprecated; use -o/--output' train_old.err)" -eq 1 ] ||
    fail "train --out: no single deprecation warning: $(cat train_old.err)"
[ "$(grep -c '^warning: --float-model is deprecated; ' train_old.err)" -eq 1 ] ||
    fail "train --float-model: no single deprecation warning: $(cat train_old.err)"
run train_new --threads 3 train "${train[@]}" --half -o new.pt &&
    grep -q "3 threads on cpu" train_new.err || fail "--threads 3 train (before the command): $(cat train_new.err)"
[ "$(warnings train_new)" -eq 0 ] || fail "train -o --half warned: $(cat train_new.err)"
if [ -s old.pt ] && [ -s new.pt ]; then
    old_size=$(wc -c <old.pt)
    new_size=$(wc -c <new.pt)
    [ "$old_size" -gt $((new_size * 18 / 10)) ] ||
        fail "float32 model $old_size bytes, --half model $new_size bytes: expected about twice"
else
    fail "train wrote no model (old.pt, new.pt)"
fi
echo "ok train_threads_output_and_precision"

[ -n "$pair" ] || { [ $failures -eq 0 ] && echo "no bundled model: predict not checked"; exit $((failures > 0)); }
one=(--ref "$pair/ref.png" --src "$pair/src.png" --cameras "$pair/cameras.json")
printf '0.2 0.3 1.2\n' >pts.txt
run predict_new predict "${one[@]}" --at 0.3,0.3,1.1 --points pts.txt -o new.vdb
for f in new.vdb new_000.exr new_001.exr; do [ -s "$f" ] || fail "predict --at --points wrote no $f"; done
for f in new_000.png new_001.png; do [ -e "$f" ] && fail "predict wrote $f without --png"; done
[ "$(warnings predict_new)" -eq 0 ] || fail "predict --at warned: $(cat predict_new.err)"
run predict_old predict "${one[@]}" --envmap-at 0.3,0.3,1.1 -o old.vdb
for f in old.vdb old_000.exr old_000.png; do [ -s "$f" ] || fail "predict --envmap-at wrote no $f"; done
[ "$(grep -c '^warning: --envmap-at is deprecated; use --at' predict_old.err)" -eq 1 ] ||
    fail "predict --envmap-at: no single deprecation warning: $(cat predict_old.err)"
echo "ok predict_at_points_png"

finish
