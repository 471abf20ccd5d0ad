#!/usr/bin/env bash
# A shell written before shells recorded their centre (here: an export of one whose manifest
# lacks `shell_centre`, as exports made then do, imported back) is still recognised as a
# shell: `info` says so and `shell` refuses it with one error line, writing nothing.
#   unmarked_shell_test.sh LIGHTHOUSE SHELL.vdb WORKDIR
set -u
[ $# -eq 3 ] || { echo "usage: $0 LIGHTHOUSE SHELL.vdb WORKDIR" >&2; exit 2; }
lh=$1
shell=$(realpath -- "$2")  # the script works inside WORKDIR
work=$3
source "$(dirname "$0")/harness.sh"
fresh_workdir "$work"

"$lh" export "$shell" --for houdini -o exp >/dev/null 2>&1 || { echo "export failed"; exit 1; }
grep -q '"shell_centre"' exp/manifest.json || fail "the export does not record the shell's centre"
# The manifest is pretty-printed with sorted keys: the centre is a block of its own, followed
# by another key, so deleting the block leaves valid JSON.
sed -i '/"shell_centre": \[/,/\],/d' exp/manifest.json
grep -q '"shell_centre"' exp/manifest.json && fail "could not remove the centre from the manifest"
"$lh" import exp --from houdini -o old.vdb >/dev/null 2>import.err ||
    { echo "import failed: $(cat import.err)"; exit 1; }

"$lh" info old.vdb >info.out 2>&1 || fail "info failed: $(cat info.out)"
grep -q "^shell: the medium collapsed around a point the file does not record" info.out ||
    fail "info does not say the file is a shell: $(cat info.out)"

"$lh" shell old.vdb -o again.vdb </dev/null >shell.out 2>shell.err
code=$?
[ $code -eq 1 ] || fail "shell of an unmarked shell: exit $code, expected 1"
[ "$(wc -l <shell.err)" -eq 1 ] || fail "expected one line on stderr: $(cat shell.err)"
grep -q "^lighthouse: error: '.*old[.]vdb' is already a shell .*written before shells recorded their centre.*predict --no-shell" \
    shell.err || fail "unexpected message: $(cat shell.err)"
[ -e again.vdb ] && fail "shell wrote again.vdb"

# The volume it was collapsed from is not mistaken for a shell.
"$lh" info ../example.vdb 2>&1 | grep -q "^shell:" && fail "info calls the example room a shell"

finish
