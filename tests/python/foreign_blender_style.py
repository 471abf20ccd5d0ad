#!/usr/bin/python3
"""lighthouse reads and renders a foreign, Blender-style file: just `density` + `color`.

usage: /usr/bin/python3 foreign_blender_style.py /path/to/lighthouse

pyopenvdb writes a FloatGrid `density` and a Vec3SGrid `color` (no metadata at all) holding
an opaque, emissive red block (sigma 50, colour (1, 0, 0)) with voxel size 0.1 occupying
world x in [1.0, 1.5], y and z in [-0.25, 0.25]. Then:
  - `lighthouse info` reports one level and no layout;
  - `lighthouse render-envmap --at 0,0,0 --at 2.5,0,0 --size 64x32 --png -o env.exr`
    writes env_000/001 .exr and .png; the PNGs (decoded here, no imaging library needed)
    show the red block at column 3W/4 (+x) on the middle rows from the origin, with the
    -x direction (column W/4) black, and the other way round from (2.5, 0, 0).
"""

import os
import sys
import tempfile

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import lh_testlib as lt  # noqa: E402

vdb, np = lt.import_openvdb()

W, H = 64, 32
VOXEL = 0.1
# Index range of the block; the transform puts voxel (i, j, k) at centre
# (0.1 i + 0.05, 0.1 j, 0.1 k), so i = 10..14 spans x in [1.0, 1.5] and j, k = -2..2 span
# [-0.25, 0.25].
I_RANGE, J_RANGE = (10, 14), (-2, 2)


def write_block(path):
    xf = [[VOXEL, 0, 0, 0], [0, VOXEL, 0, 0], [0, 0, VOXEL, 0], [VOXEL / 2, 0, 0, 1]]
    density = vdb.FloatGrid(0.0)
    density.name = "density"
    density.transform = vdb.createLinearTransform(xf)
    color = vdb.Vec3SGrid((0.0, 0.0, 0.0))
    color.name = "color"
    color.transform = vdb.createLinearTransform(xf)
    nx, ny = I_RANGE[1] - I_RANGE[0] + 1, J_RANGE[1] - J_RANGE[0] + 1
    density.copyFromArray(np.full((nx, ny, ny), 50.0, dtype=np.float32),
                          ijk=(I_RANGE[0], J_RANGE[0], J_RANGE[0]))
    rgb = np.zeros((nx, ny, ny, 3), dtype=np.float32)
    rgb[..., 0] = 1.0
    color.copyFromArray(rgb, ijk=(I_RANGE[0], J_RANGE[0], J_RANGE[0]))
    vdb.write(path, grids=[density, color])
    return density, color


def column_max(rows, col):
    return max(max(rows[r][col]) for r in range(len(rows)))


def check_envmap(t, path, bright_col, dark_col, where):
    """The block must be the bright red region around `bright_col` on the middle rows, and
    the opposite direction `dark_col` must be black."""
    try:
        w, h, rows = lt.read_png_rgb(path)
    except (OSError, ValueError) as e:
        t.check(False, "%s: cannot decode %s: %s" % (where, path, e))
        return
    if not t.equal((w, h), (W, H), "%s: PNG size" % where):
        return
    # Brightest pixel (by R + G + B) and the centroid of the bright region.
    best = max(((sum(rows[r][c]), r, c) for r in range(h) for c in range(w)))
    _, br, bc = best
    r_, g_, b_ = rows[br][bc]
    t.check(r_ >= 200 and g_ <= 20 and b_ <= 20,
            "%s: brightest pixel (row %d, column %d) is %r, expected saturated red"
            % (where, br, bc, rows[br][bc]))
    bright = [(r, c) for r in range(h) for c in range(w) if rows[r][c][0] >= 128]
    if t.check(bright, "%s: no bright pixel at all" % where):
        mr = sum(r for r, _ in bright) / len(bright)
        mc = sum(c for _, c in bright) / len(bright)
        # Pixel centres of the direction: column bright_col + 0.5 sits 2.8 degrees off the
        # axis, so the centroid of a symmetric region lies at bright_col - 0.5.
        t.check(abs(mc - (bright_col - 0.5)) <= 1.5,
                "%s: bright region centred on column %.2f, expected about %d"
                % (where, mc, bright_col))
        t.check(abs(mr - (H / 2 - 0.5)) <= 1.5,
                "%s: bright region centred on row %.2f, expected the middle (%.1f)"
                % (where, mr, H / 2 - 0.5))
        t.check(len(bright) < 0.1 * w * h,
                "%s: %d bright pixels, expected a small block" % (where, len(bright)))
        off_red = [(r, c, rows[r][c]) for r, c in bright if max(rows[r][c][1:]) > 40]
        t.check(not off_red, "%s: bright pixels that are not red: %r" % (where, off_red[:5]))
    t.check(abs(bc - bright_col) <= 3 and abs(br - (H / 2 - 0.5)) <= 2,
            "%s: brightest pixel at row %d, column %d; expected near row %g, column %d"
            % (where, br, bc, H / 2 - 0.5, bright_col))
    for c in range(dark_col - 2, dark_col + 3):
        t.check(column_max(rows, c) <= 2,
                "%s: column %d (opposite the block) is not black: max %d"
                % (where, c, column_max(rows, c)))


def decoder_self_test(t, tmp):
    """The PNG decoder itself, on an image using all five filter types."""
    path = os.path.join(tmp, "selftest.png")

    def pixel(x, y):
        return ((x * 37 + y * 11) & 255, (x * x + 3 * y) & 255, (255 - x * y) & 255)

    lt.write_png_rgb(path, 13, 10, pixel)
    w, h, rows = lt.read_png_rgb(path)
    t.equal((w, h), (13, 10), "PNG decoder self-test: size")
    wrong = [(x, y) for y in range(10) for x in range(13) if rows[y][x] != pixel(x, y)]
    t.check(not wrong, "PNG decoder self-test: %d wrong pixels, first %r" % (len(wrong), wrong[:3]))


def main():
    lighthouse = lt.lighthouse_from_argv()
    t = lt.Checks("foreign_blender_style")
    with tempfile.TemporaryDirectory(prefix="lh_foreign_blender_") as tmp:
        decoder_self_test(t, tmp)
        path = os.path.join(tmp, "blender.vdb")
        write_block(path)
        metas = vdb.readAllGridMetadata(path)
        t.equal(sorted(g.name for g in metas), ["color", "density"], "grids written by pyopenvdb")

        p = lt.run([lighthouse, "info", path])
        if t.check(p.returncode == 0, "lighthouse info failed: " + lt.describe(p)):
            t.check(": 1 level(s)" in p.stdout, "info does not report 1 level:\n" + p.stdout)
            # The level may be reported under the file's names or the normalised ones.
            t.check("level 0 (density, color" in p.stdout or
                    "level 0 (density_L0, color_L0" in p.stdout,
                    "info does not describe level 0's density and color grids:\n" + p.stdout)
            t.check("world box [1, 1.5] x [-0.25, 0.25] x [-0.25, 0.25]" in p.stdout,
                    "info does not report the block's world box:\n" + p.stdout)
            t.check("layout: none" in p.stdout, "info reports a layout for a foreign file:\n"
                    + p.stdout)
            t.check("voxel size 0.1 x 0.1 x 0.1" in p.stdout,
                    "info does not report voxel size 0.1:\n" + p.stdout)
            t.check("warning" not in p.stderr.lower(), "unexpected warnings:\n" + p.stderr)

        out = os.path.join(tmp, "env.exr")
        p = lt.run([lighthouse, "render-envmap", path, "--at", "0,0,0", "--at", "2.5,0,0",
                    "--size", "%dx%d" % (W, H), "--exposure", "1", "--png", "-o", out])
        if t.check(p.returncode == 0, "lighthouse render-envmap failed: " + lt.describe(p)):
            for i in (0, 1):
                exr = os.path.join(tmp, "env_%03d.exr" % i)
                if t.check(os.path.isfile(exr), "%s was not written" % exr):
                    with open(exr, "rb") as f:
                        t.equal(f.read(4), b"\x76\x2f\x31\x01", "%s magic number" % exr)
            # From the origin the block is at +x (column 3W/4); -x (column W/4) is empty.
            check_envmap(t, os.path.join(tmp, "env_000.png"), 3 * W // 4, W // 4,
                         "envmap at (0,0,0)")
            # From (2.5, 0, 0) it is at -x.
            check_envmap(t, os.path.join(tmp, "env_001.png"), W // 4, 3 * W // 4,
                         "envmap at (2.5,0,0)")

        # A plain PNG output, as a user would ask for it.
        png = os.path.join(tmp, "env.png")
        p = lt.run([lighthouse, "render-envmap", path, "--at", "0,0,0", "--size", "%dx%d" % (W, H),
                    "--exposure", "1", "-o", png])
        if t.check(p.returncode == 0, "render-envmap -o env.png failed: " + lt.describe(p)):
            check_envmap(t, png, 3 * W // 4, W // 4, "env.png at (0,0,0)")
    t.finish()


if __name__ == "__main__":
    main()
