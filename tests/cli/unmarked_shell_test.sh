#!/usr/bin/env bash
# A shell written before shells recorded their centre (here: an export of one whose manifest
# lacks `shell_centre`, as exports made then do, imported back) is still recognised as a
# shell: `info` says so and `shell` refuses it with one error line, writing nothing.
#   unmarked_shell_test.sh LIGHTHOUSE SHELL.vdb WORKDIR
set -u
[ $# -eq 3 ] || { echo "usage: $0 LIGHTHOUSE SHELL.vdb WORKDIR" >&2; exit 2; }
lh=$1
shell=$2
work=$3
source "$(dirname "$0")/harness.sh"
fresh_workdir "$work"

"$lh" export "$shell" --for houdini -o "$work/exp" >/dev/null 2>&1 || { echo "export failed"; exit 1; }
grep -q '"shell_centre"' "$work/exp/manifest.json" || fail "the export does not record the shell's centre"
# The manifest is pretty-printed with sorted keys: the centre is a block of its own, followed
# by another key, so deleting the block leaves valid JSON.
sed -i '/"shell_centre": \[/,/\],/d' "$work/exp/manifest.json"
grep -q '"shell_centre"' "$work/exp/manifest.json" && fail "could not remove the centre from the manifest"
"$lh" import "$work/exp" --from houdini -o "$work/old.vdb" >/dev/null 2>"$work/import.err" ||
    { echo "import failed: $(cat "$work/import.err")"; exit 1; }

"$lh" info "$work/old.vdb" >"$work/info.out" 2>&1 || fail "info failed: $(cat "$work/info.out")"
grep -q "^shell: the medium collapsed around a point the file does not record" "$work/info.out" ||
    fail "info does not say the file is a shell: $(cat "$work/info.out")"

"$lh" shell "$work/old.vdb" -o "$work/again.vdb" </dev/null >"$work/shell.out" 2>"$work/shell.err"
code=$?
[ $code -eq 1 ] || fail "shell of an unmarked shell: exit $code, expected 1"
[ "$(wc -l <"$work/shell.err")" -eq 1 ] || fail "expected one line on stderr: $(cat "$work/shell.err")"
grep -q "^lighthouse: error: '.*old[.]vdb' is already a shell .*written before shells recorded their centre.*predict --no-shell" \
    "$work/shell.err" || fail "unexpected message: $(cat "$work/shell.err")"
[ -e "$work/again.vdb" ] && fail "shell wrote again.vdb"

# The volume it was collapsed from is not mistaken for a shell.
"$lh" info "$work/../example.vdb" 2>&1 | grep -q "^shell:" && fail "info calls the example room a shell"

finish
