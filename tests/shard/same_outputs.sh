#!/usr/bin/env bash
# Helpers shared by the sharding tests (sourced): compare what one run and a merged set of
# shards wrote.
#
#   same_dataset ONE SHARDED   every example file identical; manifest.json identical but for
#                              its "seconds" lines; contact_sheet.png identical
#   same_vdb A B               identical but for the 36-byte UUID OpenVDB writes into every
#                              file's header (a fresh one each write)
#   same_file A B              byte for byte

fail() { echo "FAIL: $*" >&2; exit 1; }

same_file() { cmp -s "$1" "$2" || fail "$1 and $2 differ"; }

same_dataset() {
    local one=$1 sharded=$2 d
    [ -f "$sharded/manifest.json" ] || fail "$sharded has no manifest.json"
    for d in "$one"/[0-9]*/; do
        d=$(basename "$d")
        diff -r "$one/$d" "$sharded/$d" >/dev/null || fail "example $d of $one and $sharded differ"
    done
    [ "$(ls -d "$one"/[0-9]* | wc -l)" = "$(ls -d "$sharded"/[0-9]* | wc -l)" ] || fail "$one and $sharded hold different examples"
    diff <(grep -v '"seconds"' "$one/manifest.json") <(grep -v '"seconds"' "$sharded/manifest.json") >&2 ||
        fail "manifest.json of $one and $sharded differ beyond their timings"
    same_file "$one/contact_sheet.png" "$sharded/contact_sheet.png"
}

same_vdb() {
    local a=$1 b=$2
    [ -s "$a" ] && [ -s "$b" ] || fail "$a or $b is missing"
    [ "$(stat -c %s "$a")" = "$(stat -c %s "$b")" ] || fail "$a and $b differ in size"
    # Header: magic (8 bytes), file version (4), library version (8), grid offsets flag (1),
    # then the UUID as 36 characters.
    cmp -s <(head -c 21 "$a") <(head -c 21 "$b") || fail "$a and $b differ in their headers"
    cmp -s <(tail -c +58 "$a") <(tail -c +58 "$b") || fail "$a and $b differ"
}
