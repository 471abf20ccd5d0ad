#!/usr/bin/env bash
# No command destroys what it reads. Each case points an output at one of the command's own
# inputs, spelled another way each time (the same name, "./name", a symlink, a hard link, a
# file inside an input directory), and checks that the command refuses with one error line
# and exit 1, and that the input's bytes are unchanged. Also: an existing export is kept
# unless --force, and output names near the 255-byte limit still write.
#
#   no_lost_input.sh LIGHTHOUSE WORKDIR
set -u
[ $# -eq 2 ] || { echo "usage: $0 LIGHTHOUSE WORKDIR" >&2; exit 2; }
lh=$1
work=$2
source "$(dirname "$0")/harness.sh"
fresh_workdir "$work"
must() { "$@" >/dev/null 2>setup.err || { echo "setup failed: $*"; cat setup.err; exit 1; }; }

must "$lh" make-example --levels 2 --res 16 -o room.vdb --cameras cameras.json
must "$lh" render-view room.vdb --cameras cameras.json -o photo.png
mkdir -p gt/s0 pred/s0
must "$lh" render-envmap room.vdb --at 0,0,1 --size 32x16 -o gt/s0/env_0.exr
must "$lh" render-envmap room.vdb --at 0,0,1.1 --size 32x16 -o pred/s0/env_0.exr
must "$lh" export room.vdb --for blender -o exported
ln -s photo.png photo_link.png
ln room.vdb room_hardlink.vdb

# refused CASE_NAME PROTECTED_FILE -- COMMAND...: exit 1, one error line that names the
# clash, and PROTECTED_FILE's bytes unchanged.
refused() {
    local name=$1 protected=$2 before after code errors
    shift 3
    before=$(sha256sum <"$protected")
    "$@" </dev/null >out.txt 2>err.txt
    code=$?
    after=$(sha256sum <"$protected")
    errors=$(grep -ci error err.txt)
    [ $code -eq 1 ] || fail "$name: exit code $code, expected 1 ($(cat err.txt))"
    [ "$errors" -eq 1 ] || fail "$name: $errors error lines, expected 1 ($(cat err.txt))"
    grep -q "^lighthouse: error: .*overwrite" err.txt || fail "$name: message does not say why: $(cat err.txt)"
    [ "$before" = "$after" ] || fail "$name: '$protected' was changed"
    echo "ok $name: $(head -n 1 err.txt)"
}

refused insert_onto_its_photo photo.png -- \
    "$lh" insert room.vdb --image photo.png --cameras cameras.json --object sphere --at 0,0,2 -o ./photo.png
refused insert_onto_a_symlink_to_its_photo photo.png -- \
    "$lh" insert room.vdb --image photo.png --cameras cameras.json --object sphere --at 0,0,2 -o photo_link.png
refused compare_csv_onto_ground_truth gt/s0/env_0.exr -- \
    "$lh" compare --batch pred gt --csv gt/s0/env_0.exr
refused import_into_the_export_it_reads exported/level_0.vdb -- \
    "$lh" import exported --from blender -o exported/level_0.vdb
refused edit_onto_a_hard_link_of_its_input room.vdb -- \
    "$lh" edit room.vdb --scale-radiance 2 -o room_hardlink.vdb
refused sparsify_onto_its_input room.vdb -- \
    "$lh" sparsify room.vdb --tau 0.001 -o ./room.vdb

# An existing export, perhaps edited, is kept unless --force.
before=$(sha256sum <exported/level_0.vdb)
"$lh" export room.vdb --for blender -o exported </dev/null >out.txt 2>err.txt
code=$?
[ $code -eq 1 ] && grep -q -- "--force" err.txt || fail "export over an existing export: exit $code, $(cat err.txt)"
[ "$before" = "$(sha256sum <exported/level_0.vdb)" ] || fail "export over an existing export changed it"
"$lh" edit room.vdb --scale-radiance 3 -o brighter.vdb >/dev/null 2>&1 || fail "edit for --force case"
"$lh" export brighter.vdb --for blender -o exported --force </dev/null >out.txt 2>err.txt ||
    fail "export --force failed: $(cat err.txt)"
[ "$before" != "$(sha256sum <exported/level_0.vdb)" ] || fail "export --force did not replace the export"
echo "ok export_keeps_an_existing_export_unless_force"

# A 250-byte file name: the temporary beside it must stay within the 255-byte limit.
long=$(printf 'n%.0s' $(seq 246)).vdb
"$lh" edit room.vdb --scale-radiance 2 -o "$long" </dev/null >out.txt 2>err.txt || fail "250-byte output name: $(cat err.txt)"
[ -s "$long" ] || fail "250-byte output name: no file"
ls -a | grep -q "\.tmp" && fail "a temporary was left behind: $(ls -a | grep '\.tmp')"
echo "ok output_name_near_the_limit"

finish
