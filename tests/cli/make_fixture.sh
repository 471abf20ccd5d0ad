#!/usr/bin/env bash
# Fixture for the CLI tests: make_fixture.sh LIGHTHOUSE WORKDIR
#
# Empties WORKDIR and fills it with the inputs the other CLI tests use:
#   example.vdb, cameras.json   lighthouse make-example --levels 3 --res 16 (small and fast)
#   random.vdb                  4096 deterministic pseudo-random bytes
#   vdbheader_random.vdb        the first 64 bytes of example.vdb (a valid VDB header), then
#                               pseudo-random bytes: the OpenVDB parser itself must fail cleanly
#   empty.vdb                   zero bytes
#   text.vdb                    a text file
#   cameras_*.json              broken cameras files (negative fx, non-orthonormal rotation,
#                               no 'ref', not JSON)
#   points.txt, badpoints.txt, emptypoints.txt
#   adir/                       a directory
#   adir.vdb/                   a directory named like a volume
set -u

if [ $# -ne 2 ]; then
    echo "usage: $0 LIGHTHOUSE WORKDIR" >&2
    exit 2
fi
lh=$1
work=$2

fail() { echo "make_fixture: $*" >&2; exit 1; }

rm -rf -- "$work" || fail "cannot clear $work"
mkdir -p -- "$work/adir" "$work/adir.vdb" || fail "cannot create $work"
cd -- "$work" || fail "cannot enter $work"

"$lh" make-example --levels 3 --res 16 -o example.vdb --cameras cameras.json </dev/null ||
    fail "lighthouse make-example failed"
[ -s example.vdb ] || fail "make-example wrote no example.vdb"
[ -s cameras.json ] || fail "make-example wrote no cameras.json"

# Deterministic pseudo-random bytes (an LCG; no fork per byte).
random_bytes() {  # COUNT SEED
    local n=$1 seed=$2 i hex
    for ((i = 0; i < n; i++)); do
        seed=$(((seed * 1103515245 + 12345) & 0x7fffffff))
        printf -v hex '%02x' $(((seed >> 16) & 255))
        printf "\\x$hex"
    done
}
random_bytes 4096 12345 >random.vdb
{ head -c 64 example.vdb; random_bytes 4096 777; } >vdbheader_random.vdb
: >empty.vdb
printf 'This is a text file, not a VDB volume.\nIt has two lines.\n' >text.vdb
[ "$(wc -c <random.vdb)" -eq 4096 ] || fail "random.vdb has the wrong size"

# A valid camera; the broken files change one thing each.
camera() {  # FX R00
    cat <<EOF
{"width": 64, "height": 48, "fx": $1, "fy": 55.4, "cx": 32.0, "cy": 24.0,
 "cam_to_world": [[$2, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}
EOF
}
printf '{"ref": %s, "src": %s}\n' "$(camera 55.4 1)" "$(camera 55.4 1)" >cameras_ok.json
printf '{"ref": %s}\n' "$(camera -55.4 1)" >cameras_negative_fx.json
printf '{"ref": %s}\n' "$(camera 55.4 1.5)" >cameras_not_orthonormal.json
printf '{"src": %s}\n' "$(camera 55.4 1)" >cameras_no_ref.json
printf 'ref: {width: 64, height: 48}\nthis is not JSON\n' >cameras_not_json.json

printf '# one point per line\n0 0 1\n0.5,0,2\n\n-0.5 0.1 1.5  # trailing comment\n' >points.txt
printf '0 0 1\n1 2\n' >badpoints.txt
printf '# only a comment\n\n' >emptypoints.txt

# Two evals' metrics.csv of the same three envmaps (eval-diff): B's PSNR is up 1, 0.5 and 2 dB,
# every other metric the same.
metrics_header='example,envmap,method,psnr_all_db,angular_all_deg,psnr_observed_db,angular_observed_deg,log_lum_rmse_all,log_lum_rmse_observed,irradiance_rel_error,radiance_ratio,psnr_unobserved_db,srgb_bias_unobserved,highlight_recall,highlight_precision'
mkdir -p eval_a eval_b
rest='8,20,4,0.4,0.3,0.56,0.33,15,0.02,0.16,nan'
printf '%s\n00,0,"ours",10,%s\n00,1,"ours",12,%s\n01,0,"ours",14,%s\n' \
    "$metrics_header" "$rest" "$rest" "$rest" >eval_a/metrics.csv
printf '%s\n01,0,"ours",16,%s\n00,0,"ours",11,%s\n00,1,"ours",12.5,%s\n' \
    "$metrics_header" "$rest" "$rest" "$rest" >eval_b/metrics.csv

echo "fixture ready in $work"
