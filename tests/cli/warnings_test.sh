#!/usr/bin/env bash
# Requests that work but may not do what was meant print a "warning:" line:
#   - values beyond half precision with --half are clamped (the file holds no Inf);
#   - an envmap asked for at a point outside every level of the volume.
#   warnings_test.sh LIGHTHOUSE WORKDIR
set -u
[ $# -eq 2 ] || { echo "usage: $0 LIGHTHOUSE WORKDIR" >&2; exit 2; }
lh=$1
work=$2
rm -rf -- "$work" && mkdir -p -- "$work" && cd -- "$work" || exit 1
failures=0
fail() { echo "FAILED: $*"; failures=$((failures + 1)); }

"$lh" make-example --levels 2 --res 16 -o room.vdb >/dev/null 2>&1 || { echo "make-example failed"; exit 1; }

# A lamp of radiance 1e6 does not fit a half (max 65504): clamped to 65000 (64992 as a half),
# with a warning.
"$lh" edit room.vdb --add-box 0,0,1,0.5,0.5,1.5:1e6,1,1 --half -o bright.vdb </dev/null >out.txt 2>err.txt ||
    fail "edit --half: $(cat err.txt)"
grep -q "^warning: .* value(s) above 65000 were clamped to fit half precision" err.txt ||
    fail "edit --half gave no clamp warning: $(cat err.txt)"
"$lh" info bright.vdb >info.txt 2>&1 || fail "info bright.vdb: $(cat info.txt)"
grep -qi "inf\b\|nan" info.txt && fail "bright.vdb holds non-finite values: $(cat info.txt)"
grep -Eq "colour max component 6(499[0-9]|5000)\b" info.txt || fail "the clamped lamp is not at 65000 (to half precision): $(grep 'colour max' info.txt)"
# Without --half nothing is clamped and nothing is said.
"$lh" edit room.vdb --add-box 0,0,1,0.5,0.5,1.5:1e6,1,1 -o bright_float.vdb </dev/null >out.txt 2>err.txt ||
    fail "edit (float): $(cat err.txt)"
grep -q "^warning:" err.txt && fail "edit in float warned: $(cat err.txt)"
echo "ok half_overflow_is_clamped_with_a_warning"

"$lh" render-envmap room.vdb --at 0,0,500 --size 16x8 -o far.exr </dev/null >out.txt 2>err.txt ||
    fail "render-envmap far away: $(cat err.txt)"
grep -q "^warning: point (0, 0, 500) lies outside every level" err.txt ||
    fail "no warning for a point outside the volume: $(cat err.txt)"
"$lh" render-envmap room.vdb --at 0,0,1 --size 16x8 -o near.exr </dev/null >out.txt 2>err.txt ||
    fail "render-envmap inside: $(cat err.txt)"
grep -q "^warning:" err.txt && fail "a point inside warned: $(cat err.txt)"
echo "ok envmap_outside_every_level_warns"

[ $failures -eq 0 ] || { echo "$failures case(s) failed"; exit 1; }
echo "all cases passed"
