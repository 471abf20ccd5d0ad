#!/usr/bin/env bash
# The command grammar that every command shares (docs/cli.md):
#   - `lighthouse` alone prints the usage on stdout and exits 0; `--version` prints the
#     project's VERSION;
#   - every new spelling works, and every old one still works, with exactly one
#     "warning: OLD is deprecated; ..." line;
#   - --threads is accepted after the command word;
#   - repeatable options take one value per use, so the input volume may come after them;
#   - --half is the one precision flag: floats by default (sparsify's default was halves);
#   - --strict refuses a volume with non-finite values in every command that reads one;
#   - --png writes a PNG beside the EXR wherever images are written.
#   grammar_test.sh LIGHTHOUSE WORKDIR VERSION
set -u
[ $# -eq 3 ] || { echo "usage: $0 LIGHTHOUSE WORKDIR VERSION" >&2; exit 2; }
lh=$1
work=$2
version=$3
source "$(dirname "$0")/harness.sh"
fresh_workdir "$work"

# ok NAME ARGS...: must succeed without a deprecation warning.
ok() {
    local name=$1
    shift
    run "$name" "$@" || { fail "$name: exit $?: $(cat "$name.err")"; return 1; }
    if grep -q "is deprecated" "$name.err"; then fail "$name: a new spelling warned: $(cat "$name.err")"; fi
    return 0
}
# deprecated NAME "OLD..." ARGS...: must succeed with exactly one warning line per old spelling.
deprecated() {
    local name=$1 olds=$2 old n
    shift 2
    run "$name" "$@" || { fail "$name: exit $?: $(cat "$name.err")"; return 1; }
    for old in $olds; do
        n=$(grep -c -- "^warning: $old is deprecated; " "$name.err")
        [ "$n" -eq 1 ] || fail "$name: $n deprecation warnings for $old, expected one: $(cat "$name.err")"
    done
    return 0
}
# error NAME REGEX ARGS...: must fail with exit 1 and one stderr line "lighthouse: error: ...REGEX".
error() {
    local name=$1 re=$2 code
    shift 2
    run "$name" "$@"
    code=$?
    [ $code -eq 1 ] || fail "$name: exit $code, expected 1: $(cat "$name.err")"
    grep -v "^warning: " "$name.err" >"$name.errline"
    [ "$(wc -l <"$name.errline")" -eq 1 ] || fail "$name: expected one error line: $(cat "$name.err")"
    grep -Eq -- "^lighthouse: error: .*$re" "$name.errline" || fail "$name: stderr does not match /$re/: $(cat "$name.err")"
}
exists() { for f in "$@"; do [ -s "$f" ] || fail "'$f' was not written"; done; }
absent() { for f in "$@"; do [ -e "$f" ] && fail "'$f' should not have been written"; done; }

"$lh" make-example --levels 2 --res 16 -o room.vdb --cameras cams.json >/dev/null 2>&1 || { echo "make-example failed"; exit 1; }
"$lh" render-view room.vdb --cameras cams.json -o photo.png >/dev/null 2>&1 || { echo "render-view failed"; exit 1; }
# A volume with +Inf radiance: scaling the room's brightest colours (3.5) by 1e38 overflows floats.
"$lh" edit room.vdb --scale-radiance 1e38 -o inf.vdb >/dev/null 2>&1 || { echo "edit (Inf fixture) failed"; exit 1; }
"$lh" info inf.vdb 2>&1 | grep -q "^warning: .*+Inf" || { echo "inf.vdb holds no +Inf: the fixture is wrong"; exit 1; }
printf '0 0 1\n0.5 0 2\n' >pts.txt
tiny=(--seed 3 --count 1 --size 48x36 --envmap-size 32x16 --envmaps 1 --supersample 1)

# ---- usage and version ---------------------------------------------------------------------
run usage
code=$?
[ $code -eq 0 ] || fail "lighthouse with no arguments: exit $code, expected 0"
grep -q "^Usage: lighthouse " usage.out && grep -q "^Subcommands:" usage.out && grep -q "render-envmap" usage.out ||
    fail "lighthouse with no arguments printed no usage: $(cat usage.out usage.err)"
[ -s usage.err ] && fail "lighthouse with no arguments wrote to stderr: $(cat usage.err)"
ok version --version && [ "$(cat version.out)" = "lighthouse $version" ] ||
    fail "--version printed '$(cat version.out)', expected 'lighthouse $version'"
echo "ok usage_and_version"

# ---- --threads after the command word ------------------------------------------------------
ok threads_after info room.vdb --threads 1 && grep -q "2 level" threads_after.out || fail "info --threads 1"
ok threads_after_eq render-envmap room.vdb --at 0,0,1 --size 16x8 --threads=1 -o threads.exr && exists threads.exr
echo "ok threads_after_the_command"

# ---- -o/--output everywhere (--out was synth's, train's and the benches') --------------------
ok synth_new synth "${tiny[@]}" -o syn_new && exists syn_new/manifest.json syn_new/000000/env_0.exr
deprecated synth_old "--out" synth "${tiny[@]}" --out syn_old && exists syn_old/manifest.json
bench=(--size 16x8 --repeats 1 --methods ours-cells)
ok bench_new bench-envmap room.vdb --count 1 "${bench[@]}" --output bench_new && exists bench_new/speed_error.csv
deprecated bench_old "--points --out" bench-envmap room.vdb --points 1 "${bench[@]}" --out bench_old &&
    exists bench_old/speed_error.csv
ok bench_sparsity_new bench-sparsity room.vdb --count 1 --size 16x8 --taus 0.1 -o bs_new && exists bs_new/memory_error.csv
deprecated bench_sparsity_old "--points --out --float" bench-sparsity room.vdb --points 1 --size 16x8 --taus 0.1 \
    --float --out bs_old && exists bs_old/memory_error.csv
echo "ok output_is_dash_o_everywhere"

# ---- --count N is a number of points; --points FILE a points file ----------------------------
error bench_count_zero "--count must be in" bench-envmap room.vdb --count 0 -o bench_zero
error bench_points_zero "--count must be in" bench-envmap room.vdb --points 0 -o bench_zero
grep -q "^warning: --points is deprecated; use --count N" bench_points_zero.err || fail "bench-envmap --points 0 did not warn"
error sparsify_count_zero "--count must be in" sparsify room.vdb --count 0 -o sp_zero.vdb
error bench_sparsity_count_zero "--count must be in" bench-sparsity room.vdb --count 0 -o bs_zero
ok sparsify_new sparsify room.vdb --count 1 -o sp_new.vdb && exists sp_new.vdb
deprecated sparsify_old "--points --float" sparsify room.vdb --points 1 --float -o sp_old.vdb && exists sp_old.vdb
echo "ok count_and_points"

# ---- --exposure scales written PNGs; edit's radiance factor is --scale-radiance --------------
colour_max() { "$lh" info "$1" 2>/dev/null | grep -o "colour max component [0-9.e+]*" | head -n 1 | awk '{print $4}'; }
ok edit_new edit room.vdb --scale-radiance 2 -o e_new.vdb && exists e_new.vdb
deprecated edit_old "--exposure" edit room.vdb --exposure 2 -o e_old.vdb && exists e_old.vdb
before=$(colour_max room.vdb)
after_new=$(colour_max e_new.vdb)
after_old=$(colour_max e_old.vdb)
awk -v a="$before" -v b="$after_new" 'BEGIN { exit !(b > 1.99 * a && b < 2.01 * a) }' ||
    fail "edit --scale-radiance 2: brightest colour $before -> $after_new"
[ "$after_old" = "$after_new" ] || fail "edit --exposure 2 gave $after_old, --scale-radiance 2 gave $after_new"
echo "ok exposure_and_scale_radiance"

# ---- the input volume is a plain argument (insert's was --volume) ---------------------------
insert=(--image photo.png --cameras cams.json --object sphere --at 0,0,2 --samples 1 --no-shadows)
ok insert_new insert room.vdb "${insert[@]}" -o ins_new.png && exists ins_new.png
# After a repeatable option: one value per use, so room.vdb is the volume, not a second --at.
ok insert_volume_last insert "${insert[@]}" room.vdb -o ins_last.png && exists ins_last.png
deprecated insert_old "--volume" insert --volume room.vdb "${insert[@]}" -o ins_old.png && exists ins_old.png
deprecated insert_old_eq "--volume" insert --volume=room.vdb "${insert[@]}" -o ins_old_eq.png && exists ins_old_eq.png
error insert_no_volume "volume is required" insert "${insert[@]}" -o ins_none.png
echo "ok volume_is_positional"

# ---- --half is the one precision flag, floats by default -----------------------------------
# A lamp of 1e6 does not fit a half: clamped with a warning only where halves were asked for.
"$lh" edit room.vdb --add-box 0,0,1,0.5,0.5,1.5:1e6,1,1 -o bright.vdb >/dev/null 2>&1 || fail "edit bright.vdb"
ok sparsify_float sparsify bright.vdb --tau 1e-3 -o sp_float.vdb &&
    grep -q "sp_float.vdb on disk (float" sparsify_float.out || fail "sparsify: $(cat sparsify_float.out)"
grep -q "clamped" sparsify_float.err && fail "sparsify stored halves by default: $(cat sparsify_float.err)"
ok sparsify_half sparsify bright.vdb --tau 1e-3 --half -o sp_half.vdb &&
    grep -q "^warning: .*clamped to fit half precision (--half)" sparsify_half.err ||
    fail "sparsify --half did not clamp the lamp: $(cat sparsify_half.err)"
grep -q "sp_half.vdb on disk (half" sparsify_half.out || fail "sparsify --half: $(cat sparsify_half.out)"
echo "ok half_is_the_precision_flag"

# ---- --strict in every command that reads a volume -----------------------------------------
strict_error="'inf[.]vdb': grid 'color_L[0-9]' holds 0 NaN, [0-9]+ [+]Inf"
error strict_info "$strict_error" info inf.vdb --strict
error strict_envmap "$strict_error" render-envmap inf.vdb --at 0,0,1 --size 16x8 --strict -o s_env.exr
error strict_view "$strict_error" render-view inf.vdb --cameras cams.json --strict -o s_view.png
error strict_insert "$strict_error" insert inf.vdb "${insert[@]}" --strict -o s_ins.png
error strict_edit "$strict_error" edit inf.vdb --scale-density 2 --strict -o s_edit.vdb
error strict_sparsify "$strict_error" sparsify inf.vdb --tau 1e-3 --strict -o s_sparse.vdb
error strict_bench_envmap "$strict_error" bench-envmap inf.vdb --count 1 "${bench[@]}" --strict -o s_bench
error strict_bench_sparsity "$strict_error" bench-sparsity inf.vdb --count 1 --size 16x8 --strict -o s_bs
error strict_export "$strict_error" export inf.vdb --for blender --strict -o s_export
absent s_env.exr s_view.png s_ins.png s_edit.vdb s_sparse.vdb s_bench/speed_error.csv s_bs/memory_error.csv s_export
# Without --strict the values are sanitised, with a warning.
ok sanitised edit inf.vdb --scale-density 2 -o sanitised.vdb && grep -q "^warning: .*replaced 0 NaN, [0-9]* +Inf" sanitised.err ||
    fail "edit without --strict did not sanitise: $(cat sanitised.err)"
echo "ok strict_everywhere"

# ---- --png wherever images are written -----------------------------------------------------
ok view_png render-view room.vdb --cameras cams.json --png -o v.exr && exists v.exr v.png
ok view_exr render-view room.vdb --cameras cams.json -o v2.exr && exists v2.exr && absent v2.png
ok oracle_png oracle syn_new/000000 --levels 2 --res 8 --envmaps-out or_env --png -o or.vdb &&
    exists or.vdb or_env/env_0.exr or_env/env_0.png
error oracle_png_alone "--png requires --envmaps-out" oracle syn_new/000000 --levels 2 --res 8 --png -o or2.vdb
echo "ok png_wherever_images_are_written"

finish
