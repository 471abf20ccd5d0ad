#!/usr/bin/env bash
# `lighthouse cameras` end to end: cameras_cli.sh LIGHTHOUSE WORKDIR SCRIPTS_DIR DEMO_PAIR_DIR
#
# 1. Writes a COLMAP text model of the bundled demo pair whose world is the true one rotated
#    73 degrees, scaled by 3.7 and shifted (python3), with 41 points seen by ref at depths
#    2.0, 2.1, ..., 6.0 m (1st percentile 2.04, 99th 5.96).
# 2. `lighthouse cameras --colmap` must give back the true cameras (ref identity, src at the
#    true baseline, intrinsics kept, near/far the percentiles): checked with python3's json.
# 3. Without --baseline: a warning line, SfM units kept.
# 4. Bad inputs: one error line each and no output left behind (expect_error.sh).
# 5. When lighthouse-net is built, `lighthouse predict` accepts the file on the demo pair.
set -u
if [ $# -ne 4 ]; then
    echo "usage: $0 LIGHTHOUSE WORKDIR SCRIPTS_DIR DEMO_PAIR_DIR" >&2
    exit 2
fi
lh=$1
work=$2
scripts=$3
demo=$4
fail() { echo "cameras_cli: $*" >&2; exit 1; }

rm -rf -- "$work" && mkdir -p -- "$work" || fail "cannot create $work"
cd -- "$work" || fail "cannot enter $work"

python3 - "$demo/cameras.json" model model_radial <<'EOF' || fail "cannot write the COLMAP model"
import json, math, os, sys
truth = json.load(open(sys.argv[1]))
def mat(c): return [row[:3] for row in c["cam_to_world"][:3]]
def pos(c): return [row[3] for row in c["cam_to_world"][:3]]
def mul(a, b): return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
def mv(a, v): return [sum(a[i][k] * v[k] for k in range(3)) for i in range(3)]
def tr(a): return [list(r) for r in zip(*a)]
def axis_angle(ax, deg):
    n = math.sqrt(sum(x * x for x in ax)); x, y, z = (v / n for v in ax)
    a = math.radians(deg); c, s, t = math.cos(a), math.sin(a), 1 - math.cos(a)
    return [[t*x*x + c, t*x*y - s*z, t*x*z + s*y], [t*x*y + s*z, t*y*y + c, t*y*z - s*x],
            [t*x*z - s*y, t*y*z + s*x, t*z*z + c]]
def quat(m):  # Shepperd, (w, x, y, z)
    t = m[0][0] + m[1][1] + m[2][2]
    if t > 0:
        s = 2 * math.sqrt(1 + t)
        return [s / 4, (m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s]
    i = max(range(3), key=lambda k: m[k][k]); j, k = (i + 1) % 3, (i + 2) % 3
    s = 2 * math.sqrt(1 + m[i][i] - m[j][j] - m[k][k])
    q = [0.0] * 4
    q[0] = (m[k][j] - m[j][k]) / s; q[1 + i] = s / 4
    q[1 + j] = (m[j][i] + m[i][j]) / s; q[1 + k] = (m[k][i] + m[i][k]) / s
    return q
Q, S, T = axis_angle([0.3, -0.5, 0.8], 73.0), 3.7, [2.5, -1.25, 7.0]
def write(d, ref_model):
    os.makedirs(d, exist_ok=True)
    r = truth["ref"]
    with open(d + "/cameras.txt", "w") as f:
        f.write("# CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n")
        f.write("1 %s %d %d %r %r %r %r\n" % (ref_model, r["width"], r["height"], r["fx"],
                r["fy"], r["cx"], r["cy"]))
    pts = [(100 + k, [0.3 * math.sin(k), 0.2 * math.cos(2 * k), 1.0], 2.0 + 0.1 * k) for k in range(41)]
    with open(d + "/images.txt", "w") as f:
        for iid, name, cam in ((1, "ref.png", truth["ref"]), (2, "src.png", truth["src"])):
            R, C = mat(cam), pos(cam)
            Rc = mul(tr(R), tr(Q))
            t = [-a - S * b for a, b in zip(mv(Rc, T), mv(tr(R), C))]
            f.write("%d %s %s 1 %s\n" % (iid, " ".join(repr(v) for v in quat(Rc)),
                                         " ".join(repr(v) for v in t), name))
            f.write(" ".join("1.5 2.5 %d" % p[0] for p in pts) + "\n")
    with open(d + "/points3D.txt", "w") as f:
        for pid, ray, z in pts:
            x = [v * z for v in ray]
            w = [S * a + b for a, b in zip(mv(Q, x), T)]
            f.write("%d %r %r %r 10 20 30 0.5 1 0 2 0\n" % (pid, w[0], w[1], w[2]))
write(sys.argv[2], "PINHOLE")
write(sys.argv[3], "SIMPLE_RADIAL")
EOF
# SIMPLE_RADIAL has 4 parameters: f, cx, cy, k (the PINHOLE line's 4 numbers read as such).

baseline=$(python3 -c "import json,sys; c=json.load(open(sys.argv[1]))['src']['cam_to_world']; \
print(repr((c[0][3]**2 + c[1][3]**2 + c[2][3]**2) ** 0.5))" "$demo/cameras.json")

"$lh" cameras --colmap model --ref ref.png --src src.png --baseline "$baseline" -o cams.json \
    >out.txt 2>err.txt </dev/null || { cat out.txt err.txt; fail "lighthouse cameras --colmap failed"; }
grep -qi error err.txt && { cat err.txt; fail "stderr mentions an error"; }
grep -q "near/far from 41 3D points" out.txt || { cat out.txt; fail "no near/far line"; }

python3 - cams.json "$demo/cameras.json" <<'EOF' || fail "cams.json is not the true pair"
import json, sys
got, truth = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
def close(a, b, tol, what):
    if abs(a - b) > tol: sys.exit("%s: %r, expected %r" % (what, a, b))
for view in ("ref", "src"):
    for k in ("width", "height", "fx", "fy", "cx", "cy"):
        close(got[view][k], truth[view][k], 1e-9, view + "." + k)
    for i in range(4):
        for j in range(4):
            close(got[view]["cam_to_world"][i][j], truth[view]["cam_to_world"][i][j], 1e-9,
                  "%s.cam_to_world[%d][%d]" % (view, i, j))
close(got["near"], 2.04, 1e-9, "near")
close(got["far"], 5.96, 1e-9, "far")
print("cams.json: ref identity, src at the true baseline, intrinsics kept, near 2.04 far 5.96")
EOF

# Without --baseline: SfM units (3.7 times the metric ones) and one warning line.
"$lh" cameras --colmap model --ref ref.png --src src.png -o cams_sfm.json >out.txt 2>err.txt \
    </dev/null || fail "lighthouse cameras without --baseline failed"
grep -q "^warning: no --baseline" err.txt || { cat err.txt; fail "no warning without --baseline"; }
python3 -c "import json,sys; c=json.load(open('cams_sfm.json')); \
x=c['src']['cam_to_world'][0][3]; sys.exit(0 if abs(x - 3.7 * $baseline) < 1e-9 else 'src x %r' % x)" ||
    fail "SfM units not kept"

# Bad inputs: one error line each, no output (nor its temporary) left.
bad=0
expect() {  # REGEX ARGS...
    local re=$1
    shift
    bash "$scripts/expect_error.sh" --expect "$re" --absent bad.json -- "$lh" cameras "$@" -o bad.json ||
        bad=$((bad + 1))
}
expect "--src image 'nothere[.]png' is not in the COLMAP model" \
    --colmap model --ref ref.png --src nothere.png --baseline 0.1
expect "only PINHOLE and SIMPLE_PINHOLE.*image_undistorter" \
    --colmap model_radial --ref ref.png --src src.png --baseline 0.1
expect "--baseline must be a positive finite distance" --colmap model --ref ref.png --src src.png --baseline 0
expect "--baseline must be a positive finite distance" --colmap model --ref ref.png --src src.png --baseline -1
expect "--baseline must be a positive finite distance" --colmap model --ref ref.png --src src.png --baseline nan
expect "only 41 3D points.*need 50" --colmap model --ref ref.png --src src.png --min-points 50
expect "same image" --colmap model --ref ref.png --src ref.png
expect "no_such_model.*does not exist" --colmap no_such_model --ref ref.png --src src.png
expect "exactly one of --colmap, --exif or --photos" --baseline 0.1
expect "--exif needs --baseline" --exif "$demo/ref.png" "$demo/src.png"
expect "no usable EXIF focal length" --exif "$demo/ref.png" "$demo/src.png" --baseline 0.1
expect "'no-such-colmap' not found.*apt-get install colmap" \
    --photos "$demo/ref.png" "$demo/src.png" --colmap-bin no-such-colmap
cp model/cameras.txt cameras_backup.txt
printf '1 PINHOLE 320 240 266\n' >model/cameras.txt
expect "cameras[.]txt', line 1: cannot read a camera parameter" --colmap model --ref ref.png --src src.png
cp cameras_backup.txt model/cameras.txt
[ $bad -eq 0 ] || fail "$bad error case(s) failed"

# The file is one that predict accepts (when this build has the network).
if [ -x "$(dirname -- "$lh")/lighthouse-net" ]; then
    "$lh" predict --ref "$demo/ref.png" --src "$demo/src.png" --cameras cams.json -o pred.vdb \
        >predict.txt 2>&1 </dev/null || { cat predict.txt; fail "predict refused cams.json"; }
    [ -s pred.vdb ] || fail "predict wrote no volume"
    echo "predict accepted cams.json"
fi
echo "cameras cli: ok"
