#!/usr/bin/python3
"""lighthouse refuses broken foreign files with one clear line, and sanitises NaN/Inf.

usage: /usr/bin/python3 foreign_bad_files.py /path/to/lighthouse

Files written by pyopenvdb:
  (i)   `density` is a Vec3SGrid          -> `info` fails (exit 1) naming 'density', 'FloatGrid'
  (ii)  `density` without `color`         -> fails naming 'color'
  (iii) frustum transforms                -> fails with 'non-affine'
  (iv)  a NaN and a +Inf density voxel    -> `info` succeeds with a `warning:` line naming
                                             'density'; `info --strict` fails naming it
and a few more: `color` a FloatGrid, different transforms, NaN/negative colours, and
render-envmap on the NaN/Inf file (sanitised, or refused with --strict leaving no output).
"""

import os
import sys
import tempfile

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import lh_testlib as lt  # noqa: E402

vdb, np = lt.import_openvdb()


def block_density(value=20.0, transform=None, cls=None, name="density"):
    g = (cls or vdb.FloatGrid)(0.0 if cls in (None, vdb.FloatGrid) else (0.0, 0.0, 0.0))
    g.name = name
    g.transform = transform or vdb.createLinearTransform(0.1)
    if cls in (None, vdb.FloatGrid):
        g.copyFromArray(np.full((4, 4, 4), value, dtype=np.float32), ijk=(8, -2, -2))
    else:
        g.copyFromArray(np.full((4, 4, 4, 3), value, dtype=np.float32), ijk=(8, -2, -2))
    return g


def block_color(rgb=(1.0, 0.5, 0.25), transform=None, name="color"):
    g = vdb.Vec3SGrid((0.0, 0.0, 0.0))
    g.name = name
    g.transform = transform or vdb.createLinearTransform(0.1)
    a = np.zeros((4, 4, 4, 3), dtype=np.float32)
    a[...] = rgb
    g.copyFromArray(a, ijk=(8, -2, -2))
    return g


def error_lines(stderr):
    return [line for line in stderr.splitlines() if "error" in line.lower()]


def expect_failure(t, lighthouse, args, must_contain, what, output=None):
    """The command must exit 1 with exactly one 'lighthouse: error:' line holding every string
    of `must_contain`, and must not leave `output` behind."""
    p = lt.run([lighthouse] + args)
    ok = t.check(p.returncode == 1, "%s: exit %d, expected 1\n%s" % (what, p.returncode,
                                                                    lt.describe(p)))
    lines = error_lines(p.stderr)
    if t.check(len(lines) == 1, "%s: %d error lines on stderr, expected one:\n%s"
               % (what, len(lines), p.stderr)):
        line = lines[0]
        t.check(line.startswith("lighthouse: error: "),
                "%s: error line does not start with 'lighthouse: error: ': %r" % (what, line))
        for s in must_contain:
            t.check(s in line, "%s: error line does not mention %r: %r" % (what, s, line))
    if output is not None:
        t.check(not os.path.exists(output), "%s: output %s left behind" % (what, output))
        d, name = os.path.split(output)
        stem = os.path.splitext(name)[0]
        temps = [f for f in os.listdir(d) if f.startswith("." + stem)]
        t.check(not temps, "%s: temporaries left behind: %r" % (what, temps))
    return ok


def main():
    lighthouse = lt.lighthouse_from_argv()
    t = lt.Checks("foreign_bad_files")
    with tempfile.TemporaryDirectory(prefix="lh_foreign_bad_") as tmp:
        def path(name):
            return os.path.join(tmp, name)

        # (i) density is a Vec3SGrid.
        f = path("density_vec3.vdb")
        vdb.write(f, grids=[block_density(cls=vdb.Vec3SGrid), block_color()])
        expect_failure(t, lighthouse, ["info", f], ["'density'", "FloatGrid", f],
                       "(i) density as Vec3SGrid")
        expect_failure(t, lighthouse, ["render-envmap", f, "--at", "0,0,0", "--size", "16x8",
                                       "-o", path("env_i.exr")],
                       ["'density'", "FloatGrid"], "(i) render-envmap", output=path("env_i.exr"))

        # (ii) density without color.
        f = path("no_color.vdb")
        vdb.write(f, grids=[block_density()])
        expect_failure(t, lighthouse, ["info", f], ["color", "density", f], "(ii) no color grid")

        # (iii) frustum transforms on both grids.
        f = path("frustum.vdb")
        frustum = vdb.createFrustumTransform((0, 0, 0), (16, 16, 16), 0.5, 4.0, 0.1)
        t.check(not frustum.isLinear, "pyopenvdb made a linear 'frustum' transform")
        vdb.write(f, grids=[block_density(transform=frustum),
                            block_color(transform=frustum.deepCopy())])
        expect_failure(t, lighthouse, ["info", f], ["non-affine", f], "(iii) frustum transform")

        # (iv) a NaN and a +Inf voxel in density.
        f = path("nonfinite.vdb")
        d = block_density()
        acc = d.getAccessor()
        acc.setValueOn((9, -1, -1), float("nan"))
        acc.setValueOn((10, 0, 0), float("inf"))
        vdb.write(f, grids=[d, block_color()])
        p = lt.run([lighthouse, "info", f])
        if t.check(p.returncode == 0, "(iv) info without --strict failed:\n" + lt.describe(p)):
            warnings = [line for line in p.stderr.splitlines() if line.startswith("warning:")]
            t.check(any("'density'" in w for w in warnings),
                    "(iv) no 'warning:' line naming grid 'density':\n" + p.stderr)
            t.check(any("NaN" in w for w in warnings) and any("Inf" in w for w in warnings),
                    "(iv) the warning does not mention NaN and Inf:\n" + p.stderr)
            t.check(not error_lines(p.stderr), "(iv) error lines without --strict:\n" + p.stderr)
            t.check("1 level(s)" in p.stdout, "(iv) info does not report one level:\n" + p.stdout)
            ranges = [line for line in p.stdout.splitlines() if "density [" in line]
            t.check(ranges and not any(w in line.lower() for line in ranges
                                       for w in ("nan", "inf")),
                    "(iv) info reports non-finite density values after sanitising:\n"
                    + p.stdout)
        expect_failure(t, lighthouse, ["info", "--strict", f], ["'density'", f],
                       "(iv) info --strict with NaN/Inf")
        expect_failure(t, lighthouse, ["render-envmap", f, "--strict", "--at", "0,0,0",
                                       "--size", "16x8", "-o", path("env_strict.exr")],
                       ["'density'"], "(iv) render-envmap --strict",
                       output=path("env_strict.exr"))
        out = path("env_sanitised.png")
        p = lt.run([lighthouse, "render-envmap", f, "--at", "0,0,0", "--size", "16x8", "-o", out])
        if t.check(p.returncode == 0 and os.path.isfile(out),
                   "(iv) render-envmap without --strict failed:\n" + lt.describe(p)):
            t.check(any(line.startswith("warning:") and "'density'" in line
                        for line in p.stderr.splitlines()),
                    "(iv) render-envmap printed no warning naming 'density':\n" + p.stderr)
            w, h, rows = lt.read_png_rgb(out)
            t.check(max(max(px) for row in rows for px in row) > 0,
                    "(iv) the sanitised block renders black")

        # (v) color is a FloatGrid.
        f = path("color_float.vdb")
        bad_color = vdb.FloatGrid(0.0)
        bad_color.name = "color"
        bad_color.transform = vdb.createLinearTransform(0.1)
        bad_color.copyFromArray(np.ones((4, 4, 4), dtype=np.float32), ijk=(8, -2, -2))
        vdb.write(f, grids=[block_density(), bad_color])
        expect_failure(t, lighthouse, ["info", f], ["'color'", "Vec3SGrid"],
                       "(v) color as FloatGrid")

        # (vi) density and color with different transforms.
        f = path("mismatch.vdb")
        vdb.write(f, grids=[block_density(), block_color(transform=vdb.createLinearTransform(0.2))])
        expect_failure(t, lighthouse, ["info", f], ["transform"], "(vi) different transforms")

        # (vii) NaN and negative colour components: sanitised with a warning naming 'color'.
        f = path("color_nan.vdb")
        c = block_color()
        acc = c.getAccessor()
        acc.setValueOn((9, -1, -1), (float("nan"), 0.5, 0.5))
        acc.setValueOn((10, 0, 0), (-1.0, 0.5, 0.5))
        vdb.write(f, grids=[block_density(), c])
        p = lt.run([lighthouse, "info", f])
        if t.check(p.returncode == 0, "(vii) info failed:\n" + lt.describe(p)):
            t.check(any(line.startswith("warning:") and "'color'" in line
                        for line in p.stderr.splitlines()),
                    "(vii) no warning naming grid 'color':\n" + p.stderr)
        expect_failure(t, lighthouse, ["info", "--strict", f], ["'color'"],
                       "(vii) info --strict with NaN colour")

        # (viii) a file with other grids only.
        f = path("no_density.vdb")
        other = vdb.FloatGrid(0.0)
        other.name = "temperature"
        other.copyFromArray(np.ones((2, 2, 2), dtype=np.float32))
        vdb.write(f, grids=[other])
        expect_failure(t, lighthouse, ["info", f], ["density"], "(viii) no density grid")
    t.finish()


if __name__ == "__main__":
    main()
