#!/usr/bin/env bash
# Requests that work but may not do what was meant print a "warning:" line:
#   - values beyond half precision with --half are clamped (the file holds no Inf);
#   - an envmap asked for at a point outside every level of the volume;
#   - an inserted object that the photo will not show (behind the camera, behind the scene).
#   warnings_test.sh LIGHTHOUSE WORKDIR
set -u
[ $# -eq 2 ] || { echo "usage: $0 LIGHTHOUSE WORKDIR" >&2; exit 2; }
lh=$1
work=$2
source "$(dirname "$0")/harness.sh"
fresh_workdir "$work"

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

# The example room's reference camera sits at the origin looking along +z into a room whose
# walls lie within 10 m: a sphere at z = -2 is behind the camera, a cube at z = 30 behind the
# far wall, a sphere at z = 2 in plain view (and not in front of the cube).
"$lh" make-example --levels 2 --res 16 --cameras cams.json -o room_cam.vdb >/dev/null 2>&1 ||
    fail "make-example --cameras"
"$lh" render-view room_cam.vdb --cameras cams.json -o photo.png >/dev/null 2>&1 || fail "render-view"
"$lh" insert room_cam.vdb --image photo.png --cameras cams.json --samples 1 --no-shadows \
    --object sphere --at -0.5,0,2 --object sphere --at 0,0,-2 --object cube --at 1,0.5,30 \
    -o inserted.png </dev/null >out.txt 2>err.txt || fail "insert: $(cat err.txt)"
grep -q "^warning: object 2 (sphere at 0,0,-2) is not visible in the image: it is behind the camera" err.txt ||
    fail "no warning for the object behind the camera: $(cat err.txt)"
grep -q "^warning: object 3 (cube at 1,0.5,30) is not visible in the image: it is behind the scene's surface" err.txt ||
    fail "no warning for the object behind the wall: $(cat err.txt)"
grep -q "^warning: object 1 " err.txt && fail "the visible object warned: $(cat err.txt)"
[ -s inserted.png ] || fail "insert wrote no image"
echo "ok hidden_inserted_objects_warn"

finish
