#!/usr/bin/python3
"""python3-openvdb reads every file `lighthouse export` writes, with the names, types, vector
types and transforms Blender's and Houdini's conventions require (Houdini is not installed
here: this is how its conventions are tested).

usage: /usr/bin/python3 dcc_conventions.py /path/to/lighthouse

The example room (2 levels of 16^3: s0 = 14, level 0 spans [-7, 7]^3, level 1
[-3.5, 3.5]^2 x [0, 7]) is exported for both programs. Per level file:
  Blender: FloatGrid `density` (fog volume), FloatGrids `emission_r/g/b`, Vec3SGrid `color`
           (vector type invariant = colour); Z-up: voxel (i, j, k) of level k sits at
           Blender (x, z, -y) of its lighthouse centre, with the index shifted by -1/2
           (Blender draws voxel (i, j, k) at the centre of the cell [i, i+1]^3).
  Houdini: FloatGrid `density` (fog volume), Vec3SGrids `emission` and `Cd` (invariant, which
           Houdini shows as "Tuple/Color"); Y-up: voxel centre at Houdini (x, -y, -z).
Everywhere: `emission` = density x colour (premultiplied), no value above 65504, the level's
shell only (level 0 holds no voxel inside level 1), `level` and domain metadata on each grid,
file metadata naming the program; manifest.json lists the files, axes and index shift.
"""

import json
import os
import sys
import tempfile

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import lh_testlib as lt  # noqa: E402

vdb, np = lt.import_openvdb()

S0, RES = 14.0, 16
EXPECT = {
    "blender": {"names": {"density", "emission_r", "emission_g", "emission_b", "color"},
                "color": "color", "shift": -0.5, "axes": lambda p: (p[0], p[2], -p[1])},
    "houdini": {"names": {"density", "emission", "Cd"},
                "color": "Cd", "shift": 0.0, "axes": lambda p: (p[0], -p[1], -p[2])},
}


def level_box(k):
    s = S0 / 2 ** k
    return ((-s / 2, -s / 2, -s / 2), (s / 2, s / 2, s / 2)) if k == 0 else ((-s / 2, -s / 2, 0.0), (s / 2, s / 2, s))


def check_export(t, path, program):
    e = EXPECT[program]
    with open(os.path.join(path, "manifest.json")) as f:
        manifest = json.load(f)
    t.equal(manifest.get("for"), program, "%s manifest 'for'" % program)
    t.equal(manifest.get("index_shift"), e["shift"], "%s manifest index_shift" % program)
    t.equal([lvl["file"] for lvl in manifest["levels"]], ["level_0.vdb", "level_1.vdb"], "%s level files" % program)
    for k in range(2):
        fpath = os.path.join(path, "level_%d.vdb" % k)
        grids, meta = vdb.readAll(fpath)
        by = {g.name: g for g in grids}
        what = "%s level %d" % (program, k)
        t.equal(set(by), e["names"], what + " grid names")
        t.equal(meta.get("lighthouse_export_for"), program, what + " file metadata lighthouse_export_for")
        density = by.get("density")
        color = by.get(e["color"])
        if not (density and color):
            continue
        t.equal(type(density).__name__, "FloatGrid", what + " density type")
        t.equal(density.gridClass, vdb.GridClass.FOG_VOLUME, what + " density grid class")
        t.equal(type(color).__name__, "Vec3SGrid", what + " colour type")
        t.equal(color.vectorType, vdb.VectorType.INVARIANT, what + " colour vector type")
        if program == "houdini":
            t.equal(type(by["emission"]).__name__, "Vec3SGrid", what + " emission type")
            t.equal(by["emission"].vectorType, vdb.VectorType.INVARIANT, what + " emission vector type")
        else:
            for n in ("emission_r", "emission_g", "emission_b"):
                t.equal(type(by[n]).__name__, "FloatGrid", what + " %s type" % n)
        for g in grids:
            t.equal(g.metadata.get("level"), k, what + " %s level metadata" % g.name)
            t.check("lighthouse_domain_min" in g.metadata, what + " %s has no domain metadata" % g.name)
        # Transforms: voxel size and where voxels (0,0,0) and (R-1,...) land in the program's axes.
        voxel = S0 / 2 ** k / RES
        lo, hi = level_box(k)
        for g in grids:
            xf = g.transform
            t.check(xf.isLinear, what + " %s transform is not linear" % g.name)
            t.close(xf.voxelSize(), (voxel,) * 3, what + " %s voxel size" % g.name, 1e-9)
            for ijk, world in (((0, 0, 0), tuple(c + voxel / 2 for c in lo)),
                               ((RES - 1,) * 3, tuple(c - voxel / 2 for c in hi))):
                shifted = tuple(i - e["shift"] for i in ijk)  # where the program draws voxel ijk
                t.close(xf.indexToWorld(shifted), e["axes"](world),
                        what + " %s index %r -> program world" % (g.name, ijk), 1e-9)
        # Values: premultiplied emission, within half precision, and the shell only.
        dens = np.zeros((RES,) * 3, np.float32)
        density.copyToArray(dens, ijk=(0, 0, 0))
        col = np.zeros((RES,) * 3 + (3,), np.float32)
        color.copyToArray(col, ijk=(0, 0, 0))
        emi = np.zeros((RES,) * 3 + (3,), np.float32)
        if program == "houdini":
            by["emission"].copyToArray(emi, ijk=(0, 0, 0))
        else:
            for c, n in enumerate(("emission_r", "emission_g", "emission_b")):
                ch = np.zeros((RES,) * 3, np.float32)
                by[n].copyToArray(ch, ijk=(0, 0, 0))
                emi[..., c] = ch
        t.check(dens.max() > 0, what + " density is empty")
        t.check(np.allclose(emi, dens[..., None] * col, rtol=1e-6, atol=1e-6), what + " emission != density x colour")
        t.check(dens.max() <= 65504 and emi.max() <= 65504, what + " values above the half-precision limit")
        if k == 0:
            # Level 0 voxels with centres inside level 1's box [-3.5, 3.5]^2 x [0, 7] are empty.
            idx = np.argwhere(dens > 0)
            inside = 0
            for i, j, l in idx:
                p = [lo[a] + voxel * (c + 0.5) for a, c in enumerate((i, j, l))]
                inside += all(level_box(1)[0][a] <= p[a] <= level_box(1)[1][a] for a in range(3))
            t.equal(inside, 0, what + " shell voxels inside the finer level")


def main():
    lighthouse = lt.lighthouse_from_argv()
    t = lt.Checks("dcc_conventions")
    with tempfile.TemporaryDirectory(prefix="lh_dcc_conv_") as tmp:
        room = os.path.join(tmp, "room.vdb")
        p = lt.run([lighthouse, "make-example", "--levels", "2", "--res", str(RES), "-o", room])
        t.check(p.returncode == 0, "make-example failed: " + lt.describe(p))
        for program in ("blender", "houdini"):
            out = os.path.join(tmp, program)
            p = lt.run([lighthouse, "export", room, "--for", program, "-o", out])
            if t.check(p.returncode == 0, "export --for %s failed: %s" % (program, lt.describe(p))):
                t.check("level_0.vdb" in p.stdout and program in p.stdout, "export output:\n" + p.stdout)
                check_export(t, out, program)
                # vdb_print reads them too (OpenVDB's own tool), when installed.
                if os.access("/usr/bin/vdb_print", os.X_OK):
                    q = lt.run(["/usr/bin/vdb_print", os.path.join(out, "level_1.vdb")])
                    t.check(q.returncode == 0 and "density" in q.stdout, "vdb_print failed: " + lt.describe(q))
    t.finish()


if __name__ == "__main__":
    main()
