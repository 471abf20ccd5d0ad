#!/usr/bin/env bash
# End-to-end test of `lighthouse compare`: compare_test.sh LIGHTHOUSE SCRIPTS_DIR
#
# Runs in the CLI fixture directory (it renders envmaps of its example.vdb) and works in
# compare_test/ there. Checks single comparisons (identical maps -> inf PSNR and 0 for the
# other three metrics, different maps -> finite values, a volume twice as bright -> an
# irradiance error of exactly 1.00, a full mask reproduces "all content", an empty mask
# reports no observed pixels), batch mode (directory walk that skips _pos.exr files and
# masks, masks beside the ground truth, CSV rows that agree with the printed means, progress
# on stderr for more than 20 envmaps) and the errors (size mismatches, missing prediction).
# Masks are PNGs written by /usr/bin/python3 (zlib only). Exits 0 (pass), 1 (fail) or 77
# (skipped: /usr/bin/python3 is missing).
set -u

if [ $# -ne 2 ]; then
    echo "usage: $0 LIGHTHOUSE SCRIPTS_DIR" >&2
    exit 2
fi
lh=$1
scripts=$2
python=/usr/bin/python3
[ -x "$python" ] || { echo "SKIP: $python not found"; exit 77; }

source "$(dirname "$0")/harness.sh"
ok() { bash "$scripts/expect_success.sh" "$@" || failures=$((failures + 1)); }
error() { bash "$scripts/expect_error.sh" "$@" || failures=$((failures + 1)); }

fresh_workdir compare_test

# Three 32x16 envmaps at different points (a_000..a_002.exr) and one 16x8 (small.exr/.png).
"$lh" render-envmap ../example.vdb --at 0,0,1 --at 0.3,0,1.5 --at -0.2,0.1,2 --size 32x16 \
    -o a.exr 2>/dev/null || { echo "render-envmap failed"; exit 1; }
"$lh" render-envmap ../example.vdb --at 0,0,1 --size 16x8 --png -o small.exr 2>/dev/null ||
    { echo "render-envmap failed"; exit 1; }

# write_mask PATH WIDTH HEIGHT all|none|left: 8-bit grey PNG, 255 = observed.
write_mask() {
    "$python" - "$@" <<'EOF'
import struct, sys, zlib
path, width, height, kind = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
def value(column):
    return {"all": 255, "none": 0, "left": 255 if column < width // 2 else 0}[kind]
raw = b"".join(b"\0" + bytes(value(c) for c in range(width)) for _ in range(height))
def chunk(tag, data):
    return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data))
with open(path, "wb") as f:
    f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))
EOF
}
write_mask mask_all.png 32 16 all
write_mask mask_none.png 32 16 none
write_mask mask_left.png 32 16 left

# Column COLUMN (awk field) of the stdout row starting with LABEL ("all" or "observed").
value_of() { awk -v label="$1" -v column="$2" '$1 == label { print $column }'; }

# ---- single comparisons ----------------------------------------------------------------------
num="[0-9]+[.][0-9]{2}"
ok --stdout "^ +PSNR [(]dB[)] +RGB angular error [(]deg[)] +log-luminance RMSE +irradiance rel[.] error +radiance ratio$" \
   --stdout "^all content +inf +0[.]00 +0[.]00 +0[.]00 +1[.]00$" -- "$lh" compare a_000.exr a_000.exr
ok --stdout "^all content +$num +$num +$num +$num +$num$" -- "$lh" compare a_000.exr a_001.exr
# Every radiance doubled (the same volume at exposure 2): the irradiance is off by exactly
# the truth's own size, the mean radiance is twice the truth's, the RGB angle is unchanged.
"$lh" edit ../example.vdb --scale-radiance 2 -o bright.vdb >/dev/null 2>&1 &&
    "$lh" render-envmap bright.vdb --at 0,0,1 --size 32x16 -o bright.exr 2>/dev/null ||
    { echo "edit/render-envmap failed"; exit 1; }
ok --stdout "^all content +$num +0[.]00 +$num +1[.]00 +2[.]00$" -- "$lh" compare bright.exr a_000.exr
# Lamps and windows: the example's envmap has some (its lamp); at 1000 times its radiance every
# pixel is above luminance 1, at a thousandth none is.
for scale in 1000 0.001; do
    "$lh" edit ../example.vdb --scale-radiance $scale -o scaled.vdb >/dev/null 2>&1 &&
        "$lh" render-envmap scaled.vdb --at 0,0,1 --size 32x16 -o scaled_$scale.exr 2>/dev/null ||
        { echo "edit/render-envmap failed"; exit 1; }
done
highlights="^lamps and windows [(]luminance > 1[)] within 10 deg: recall"
ok --stdout "$highlights 1[.]00, precision 1[.]00$" -- "$lh" compare a_000.exr a_000.exr
ok --stdout "$highlights none, precision none$" -- "$lh" compare scaled_0.001.exr scaled_0.001.exr
ok --stdout "$highlights 0[.]00, precision none$" -- "$lh" compare scaled_0.001.exr a_000.exr
ok --stdout "$highlights none, precision 0[.]00$" -- "$lh" compare scaled_1000.exr scaled_0.001.exr
ok --stdout "$highlights 1[.]00, precision 0[.][0-9]{2}$" -- "$lh" compare scaled_1000.exr a_000.exr
# A radius of 180 degrees matches any highlight to any other: the envmap that is white all
# over now has precision 1 against the one with a lamp. A radius of 0 matches nothing: refused.
ok --stdout "^lamps and windows [(]luminance > 1[)] within 180 deg: recall 1[.]00, precision 1[.]00$" \
   -- "$lh" compare scaled_1000.exr a_000.exr --highlight-radius 180
error --expect "--highlight-radius" -- "$lh" compare scaled_1000.exr a_000.exr --highlight-radius 0
out=$("$lh" compare a_000.exr a_001.exr --mask mask_all.png 2>&1)
psnr_all=$(value_of all 3 <<<"$out")
[ "$psnr_all" != inf ] && [ -n "$psnr_all" ] || fail "different envmaps: PSNR '$psnr_all'"
[ "$psnr_all" = "$(value_of observed 3 <<<"$out")" ] &&
    [ "$(value_of all 4 <<<"$out")" = "$(value_of observed 4 <<<"$out")" ] &&
    [ "$(value_of all 5 <<<"$out")" = "$(value_of observed 5 <<<"$out")" ] ||
    fail "a mask of every pixel must reproduce 'all content': $out"
out=$("$lh" compare a_000.exr a_001.exr --mask mask_left.png 2>&1)
grep -Eq "^observed content +$num +$num +$num +- +-$" <<<"$out" ||
    fail "half mask: no observed row: $out"
[ "$(value_of observed 3 <<<"$out")" != "$psnr_all" ] || fail "half mask changed nothing: $out"
ok --stdout "^observed content +no observed pixels" -- "$lh" compare a_000.exr a_001.exr --mask mask_none.png
# The unobserved half of an exact prediction: no bias, and nothing left once it is taken out.
ok --stdout "^display bias over unobserved content: [+]0[.]0000 .*; without it, PSNR inf dB$" \
   -- "$lh" compare a_000.exr a_000.exr --mask mask_left.png

error --expect "16x8.*32x16" -- "$lh" compare small.exr a_000.exr
error --expect "mask 'small[.]png' is 16x8 but the envmap is 32x16" -- \
    "$lh" compare a_000.exr a_001.exr --mask small.png
error --expect "no_such[.]exr.*no such file" -- "$lh" compare no_such.exr a_000.exr

# ---- batch mode ------------------------------------------------------------------------------
# gt/scene_a/env_0.exr with a half mask and a (16x8, would fail) _pos file; gt/scene_b/env_0
# and env_1 without masks. Every prediction differs from its ground truth.
mkdir -p gt/scene_a gt/scene_b pred/scene_a pred/scene_b
cp a_000.exr gt/scene_a/env_0.exr
cp small.exr gt/scene_a/env_0_pos.exr
cp mask_left.png gt/scene_a/env_0_mask.png
cp a_001.exr gt/scene_b/env_0.exr
cp a_002.exr gt/scene_b/env_1.exr
cp a_001.exr pred/scene_a/env_0.exr
cp a_002.exr pred/scene_b/env_0.exr
cp a_000.exr pred/scene_b/env_1.exr

ok --stdout "^3 envmaps, 1 with an observed mask" \
   --stdout "^all content +$num ± $num +$num ± $num +$num ± $num +$num ± $num +$num ± $num$" \
   --stdout "^observed content +$num ± 0[.]00 +$num ± 0[.]00 +$num ± 0[.]00 +- +-$" \
   --stdout "^unobserved content +$num ± 0[.]00 +- +- +- +-$" \
   --stdout "^display bias over unobserved content: [+-]0[.][0-9]{4} .*; without it, PSNR ($num|inf) dB$" \
   --stdout "$highlights ($num ± $num( [(][12] of 3[)])?|none), precision ($num ± $num( [(][12] of 3[)])?|none)$" \
   --file rows.csv -- "$lh" compare --batch pred gt --csv rows.csv
if [ -s rows.csv ]; then
    [ "$(head -n 1 rows.csv)" = "envmap,psnr_all_db,angular_all_deg,psnr_observed_db,angular_observed_deg,log_lum_rmse_all,log_lum_rmse_observed,irradiance_rel_error,radiance_ratio,psnr_unobserved_db,srgb_bias_unobserved,highlight_recall,highlight_precision" ] ||
        fail "CSV header: $(head -n 1 rows.csv)"
    [ "$(tail -n +2 rows.csv | cut -d, -f1 | tr '\n' ' ')" = \
      "scene_a/env_0.exr scene_b/env_0.exr scene_b/env_1.exr " ] || fail "CSV rows: $(cat rows.csv)"
    awk -F, 'NR > 1 && (($4 == "nan") != ($1 != "scene_a/env_0.exr") || ($4 == "nan") != ($7 == "nan")) { bad = 1 } END { exit bad }' rows.csv ||
        fail "CSV: only scene_a/env_0.exr has observed metrics: $(cat rows.csv)"
    # The printed means are the means of the CSV rows.
    out=$("$lh" compare --batch pred gt 2>&1)
    # CSV columns 2, 3, 6, 8 (PSNR, angle, log-luminance, irradiance, all content) are the
    # means in fields 3, 6, 9, 12 of the "all content" row ("mean ± std" is three fields).
    for pair in 2:3 3:6 6:9 8:12; do
        column=${pair%:*} field=${pair#*:}
        mean=$(awk -F, -v c=$column 'NR > 1 { s += $c; n++ } END { printf "%.2f", s / n }' rows.csv)
        [ "$(value_of all $field <<<"$out")" = "$mean" ] ||
            fail "CSV column $column mean $mean does not match the table: $out"
    done
    # Single mode on the masked pair gives the same numbers as its CSV row.
    single=$("$lh" compare pred/scene_a/env_0.exr gt/scene_a/env_0.exr --mask gt/scene_a/env_0_mask.png)
    row=$(awk -F, '$1 == "scene_a/env_0.exr" { printf "%.2f %.2f", $4, $5 }' rows.csv)
    [ "$(value_of observed 3 <<<"$single") $(value_of observed 4 <<<"$single")" = "$row" ] ||
        fail "batch row '$row' differs from single mode: $single"
fi

# More than 20 envmaps: progress lines on stderr, the last one the total.
mkdir -p many/gt many/pred
for k in $(seq 0 24); do cp a_000.exr many/gt/env_$k.exr; cp a_001.exr many/pred/env_$k.exr; done
"$lh" compare --batch many/pred many/gt >/dev/null 2>progress.txt || fail "batch of 25 failed"
[ "$(tail -n 1 progress.txt)" = "compared 25/25 envmaps" ] || fail "progress: $(cat progress.txt)"

# A prediction without any highlight has no precision: the count says 2 of the 3 envmaps.
cp scaled_0.001.exr pred/scene_b/env_1.exr
ok --stdout "$highlights $num ± $num, precision $num ± $num [(]2 of 3[)]$" \
   -- "$lh" compare --batch pred gt

rm pred/scene_b/env_1.exr
error --expect "no prediction 'pred/scene_b/env_1[.]exr' for ground truth 'gt/scene_b/env_1[.]exr'" \
      --absent rows_missing.csv -- "$lh" compare --batch pred gt --csv rows_missing.csv
cp small.exr pred/scene_b/env_1.exr
error --expect "pred/scene_b/env_1[.]exr' vs 'gt/scene_b/env_1[.]exr': .*16x8.*32x16" \
      --absent rows_small.csv -- "$lh" compare --batch pred gt --csv rows_small.csv
error --expect "no envmaps env_<k>[.]exr under '[.][.]/adir'" -- "$lh" compare --batch pred ../adir

finish
