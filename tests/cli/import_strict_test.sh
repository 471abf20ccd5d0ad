#!/usr/bin/env bash
# `import --strict` means what --strict means for every command that reads a volume: an
# export holding NaN, Inf or negative values (an edit in Blender or Houdini may put them
# there) is refused with one error line naming the level file and the grid, and nothing is
# written; without --strict the values are replaced, with a warning. A clean export imports
# with --strict.
#   import_strict_test.sh LIGHTHOUSE SET_VOXEL_VALUE WORKDIR
set -u
[ $# -eq 3 ] || { echo "usage: $0 LIGHTHOUSE SET_VOXEL_VALUE WORKDIR" >&2; exit 2; }
lh=$1
set_value=$2
work=$3
source "$(dirname "$0")/harness.sh"
fresh_workdir "$work"
# error NAME REGEX ARGS...: exit 1, one stderr line "lighthouse: error: ...REGEX".
error() {
    local name=$1 re=$2 code
    shift 2
    run "$name" "$@"
    code=$?
    [ $code -eq 1 ] || fail "$name: exit $code, expected 1: $(cat "$name.err")"
    [ "$(wc -l <"$name.err")" -eq 1 ] || fail "$name: expected one line on stderr: $(cat "$name.err")"
    grep -Eq -- "^lighthouse: error: .*$re" "$name.err" || fail "$name: stderr does not match /$re/: $(cat "$name.err")"
}

"$lh" make-example --levels 2 --res 16 -o room.vdb >/dev/null 2>&1 || { echo "make-example failed"; exit 1; }
for dcc in houdini blender; do
    "$lh" export room.vdb --for $dcc -o "exp_$dcc" >/dev/null 2>&1 || { echo "export --for $dcc failed"; exit 1; }
done
run clean import exp_houdini --from houdini --strict -o clean.vdb || fail "a clean export with --strict: $(cat clean.err)"
[ -s clean.vdb ] || fail "import --strict of a clean export wrote nothing"

cp -a exp_houdini nan_houdini
"$set_value" nan_houdini/level_0.vdb density nan || exit 1
error houdini_nan "'nan_houdini/level_0[.]vdb': grid 'density' holds [1-9][0-9]* NaN, 0 [+]Inf, 0 negative value[(]s[)]" \
    import nan_houdini --from houdini --strict -o nan.vdb
[ -e nan.vdb ] && fail "import --strict wrote nan.vdb"
run houdini_sanitised import nan_houdini --from houdini -o sanitised.vdb || fail "import without --strict: $(cat houdini_sanitised.err)"
grep -q "^warning: 'nan_houdini/level_0[.]vdb': replaced [1-9][0-9]* NaN/Inf/negative" houdini_sanitised.err ||
    fail "import without --strict did not say it replaced the NaN: $(cat houdini_sanitised.err)"

# Blender: a negative colour; the colour grid was edited and the emission not, so the colour is read.
cp -a exp_blender neg_blender
"$set_value" neg_blender/level_1.vdb color -1 || exit 1
error blender_negative "'neg_blender/level_1[.]vdb': grid 'color' holds 0 NaN, 0 [+]Inf, [1-9][0-9]* negative value[(]s[)]" \
    import neg_blender --from blender --strict -o neg.vdb
[ -e neg.vdb ] && fail "import --strict wrote neg.vdb"
cp -a exp_blender inf_blender
"$set_value" inf_blender/level_0.vdb density inf || exit 1
error blender_inf "'inf_blender/level_0[.]vdb': grid 'density' holds 0 NaN, [1-9][0-9]* [+]Inf" \
    import inf_blender --from blender --strict -o inf.vdb
run help import --help && grep -q -- "--strict" help.out || fail "import --help does not list --strict"

finish
