#!/usr/bin/python3
"""Blender's Cycles renders a `lighthouse export --for blender` like lighthouse renders the original.

usage: /usr/bin/python3 dcc_blender_cycles.py /path/to/lighthouse

Needs Blender (Debian's `blender`, 3.4) on PATH or at /usr/bin/blender; exits 77 (skip) with a
message when it is absent. Two checks:

1. Known answer for the axes and the envmap orientation: a one-level volume (written here with
   pyopenvdb in lighthouse's frame) holds an opaque red block (radiance (1, 0, 0)) at +x and an
   opaque green one at -y (up). Exported for Blender and rendered by Cycles from the origin
   (houdini_export/scripts/blender_lighting_volume.py, PNG), the red block must be centred on
   column 3W/4 and the middle rows, at full brightness (radiance 1 -> sRGB 255), and the green
   one must fill the top rows.
2. Agreement: the example room (3 levels of 32^3, `make-example`) exported for Blender and
   rendered by Cycles at two points, one in the middle level (0, 0, 2) and one in the finest
   (0.2, 0.1, 0.45), against `lighthouse render-envmap` of the original at the same points:
   PSNR (image/metrics.h, via `lighthouse compare`) at least 30 dB each. This covers the
   format, the axes, the half-voxel convention, the units and the shells at once: a wrong axis
   or a missing shell costs far more than 10 dB. Cycles at 32 samples, 64x32, volume step 1/4
   voxel measured 34.0 and 36.1 dB; the rest is Cycles' step jitter and its sampling of the
   trilinear ramps at level boundaries.
"""

import os
import re
import shutil
import sys
import tempfile
import time

sys.dont_write_bytecode = True
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import lh_testlib as lt  # noqa: E402

SCRIPT = os.path.join(HERE, "..", "..", "houdini_export", "scripts", "blender_lighting_volume.py")
W, H = 64, 32
MIN_PSNR_DB = 30.0
POINTS = ["0,0,2", "0.2,0.1,0.45"]


def find_blender():
    exe = shutil.which("blender") or ("/usr/bin/blender" if os.access("/usr/bin/blender", os.X_OK) else None)
    if not exe:
        print("SKIP: Blender is not installed (apt-get install blender; scripts/install_deps.sh does)")
        sys.exit(lt.SKIP)
    return exe


def blender_envmap(t, blender, export_dir, at, out, what):
    start = time.time()
    p = lt.run([blender, "-b", "--factory-startup", "--python", SCRIPT, "--", "--export", export_dir,
                "--envmap", out, "--at", at, "--size", "%dx%d" % (W, H), "--samples", "32",
                "--step-rate", "0.25"], timeout=600)
    ok = t.check(p.returncode == 0 and os.path.isfile(out), "%s: Blender failed: %s" % (what, lt.describe(p)))
    print("%s: Cycles envmap at %s in %.1f s" % (what, at, time.time() - start))
    return ok


def write_blocks(vdb, np, path):
    """Red block at +x (x in [1.0, 1.5]), green block at -y (up, y in [-1.5, -1.0]), sigma 200
    (opaque over 0.1 m voxels), radiance 1 in one channel. Voxel (i, j, k) is centred at
    0.1 (i, j, k) + 0.05, the way lighthouse's layouts place voxels."""
    xf = [[0.1, 0, 0, 0], [0, 0.1, 0, 0], [0, 0, 0.1, 0], [0.05, 0.05, 0.05, 1]]
    density = vdb.FloatGrid(0.0)
    density.name = "density"
    color = vdb.Vec3SGrid((0.0, 0.0, 0.0))
    color.name = "color"
    for g in (density, color):
        g.transform = vdb.createLinearTransform(xf)
    for ijk, rgb in (((10, -3, -3), (1.0, 0.0, 0.0)), ((-3, -15, -3), (0.0, 1.0, 0.0))):
        density.copyFromArray(np.full((5, 6, 6) if rgb[0] else (6, 5, 6), 200.0, np.float32), ijk=ijk)
        shape = (5, 6, 6, 3) if rgb[0] else (6, 5, 6, 3)
        c = np.zeros(shape, np.float32)
        c[...] = rgb
        color.copyFromArray(c, ijk=ijk)
    vdb.write(path, grids=[density, color])


def check_orientation(t, png):
    w, h, rows = lt.read_png_rgb(png)
    if not t.equal((w, h), (W, H), "block envmap size"):
        return
    red = [(r, c) for r in range(h) for c in range(w) if rows[r][c][0] >= 128 and rows[r][c][1] < 64]
    green = [(r, c) for r in range(h) for c in range(w) if rows[r][c][1] >= 128 and rows[r][c][0] < 64]
    if t.check(red, "no red pixels: the +x block is missing from the Cycles envmap"):
        mr = sum(r for r, _ in red) / len(red)
        mc = sum(c for _, c in red) / len(red)
        # The block spans x in [1, 1.5], y, z in [-0.3, 0.3]: symmetric about +x, so its
        # centroid sits on the boundary between columns 3W/4 - 1 and 3W/4 and rows H/2 - 1, H/2.
        t.check(abs(mc - (3 * W / 4 - 0.5)) <= 0.75, "red (+x) block centred on column %.2f, expected %.1f (3W/4)"
                % (mc, 3 * W / 4 - 0.5))
        t.check(abs(mr - (H / 2 - 0.5)) <= 0.75, "red (+x) block centred on row %.2f, expected %.1f"
                % (mr, H / 2 - 0.5))
        core = rows[H // 2][3 * W // 4]
        t.check(core[0] >= 250, "red block centre pixel %r: expected full radiance 1 (sRGB 255)" % (core,))
    if t.check(green, "no green pixels: the -y (up) block is missing"):
        t.check(max(r for r, _ in green) <= 4, "green (-y, up) block reaches row %d; expected the top rows"
                % max(r for r, _ in green))
        t.check(min(r for r, _ in green) == 0, "green (up) block does not touch row 0")
    lit = [(r, c, rows[r][c]) for r in range(7, h) for c in range(0, W // 2 - 4) if max(rows[r][c]) > 2]
    t.check(not lit, "the -x side below the top rows should be black: %r" % lit[:5])


def main():
    lighthouse = lt.lighthouse_from_argv()
    vdb, np = lt.import_openvdb()
    blender = find_blender()
    t = lt.Checks("dcc_blender_cycles")
    start = time.time()
    with tempfile.TemporaryDirectory(prefix="lh_dcc_cycles_") as tmp:
        # 1. Orientation known answer.
        blocks = os.path.join(tmp, "blocks.vdb")
        write_blocks(vdb, np, blocks)
        exp = os.path.join(tmp, "blocks_blender")
        p = lt.run([lighthouse, "export", blocks, "--for", "blender", "-o", exp])
        if t.check(p.returncode == 0, "export of the block volume failed: " + lt.describe(p)):
            png = os.path.join(tmp, "blocks.png")
            if blender_envmap(t, blender, exp, "0,0,0", png, "blocks"):
                check_orientation(t, png)

        # The script's other mode and its bad input: a .blend is saved; a directory that is
        # not an export gives exit 1 and one error line, and writes nothing.
        blend = os.path.join(tmp, "blocks.blend")
        p = lt.run([blender, "-b", "--factory-startup", "--python", SCRIPT, "--", "--export", exp,
                    "--save-blend", blend, "--at", "0,0,0"], timeout=300)
        t.check(p.returncode == 0 and os.path.getsize(blend) > 0 if os.path.exists(blend) else False,
                "--save-blend failed: " + lt.describe(p))
        bad = os.path.join(tmp, "not_an_export")
        os.mkdir(bad)
        p = lt.run([blender, "-b", "--factory-startup", "--python", SCRIPT, "--", "--export", bad,
                    "--envmap", os.path.join(tmp, "bad.exr"), "--at", "0,0,0"], timeout=300)
        t.check(p.returncode == 1 and "blender_lighting_volume: error: " in p.stderr and "manifest.json" in p.stderr
                and not os.path.exists(os.path.join(tmp, "bad.exr")),
                "a non-export directory must fail with one error line: " + lt.describe(p))

        # 2. Agreement on the example room at two points.
        room = os.path.join(tmp, "room.vdb")
        p = lt.run([lighthouse, "make-example", "--levels", "3", "--res", "32", "-o", room])
        t.check(p.returncode == 0, "make-example failed: " + lt.describe(p))
        exp = os.path.join(tmp, "room_blender")
        p = lt.run([lighthouse, "export", room, "--for", "blender", "-o", exp])
        t.check(p.returncode == 0, "export of the room failed: " + lt.describe(p))
        ours = os.path.join(tmp, "ours.exr")
        p = lt.run([lighthouse, "render-envmap", room] + sum([["--at", a] for a in POINTS], []) +
                   ["--size", "%dx%d" % (W, H), "-o", ours])
        t.check(p.returncode == 0, "render-envmap failed: " + lt.describe(p))
        for i, at in enumerate(POINTS):
            cyc = os.path.join(tmp, "cycles_%d.exr" % i)
            if not blender_envmap(t, blender, exp, at, cyc, "room"):
                continue
            p = lt.run([lighthouse, "compare", cyc, os.path.join(tmp, "ours_%03d.exr" % i)])
            m = re.search(r"all content\s+([0-9.]+|inf)", p.stdout)
            if t.check(p.returncode == 0 and m, "compare failed: " + lt.describe(p)):
                db = float(m.group(1))
                print("PSNR Cycles vs lighthouse at (%s): %.2f dB" % (at, db))
                t.check(db >= MIN_PSNR_DB, "Cycles and lighthouse disagree at (%s): PSNR %.2f dB < %.0f dB"
                        % (at, db, MIN_PSNR_DB))
    print("dcc_blender_cycles: %.1f s in all" % (time.time() - start))
    t.finish()


if __name__ == "__main__":
    main()
