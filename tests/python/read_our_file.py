#!/usr/bin/python3
"""python3-openvdb reads a volume written by `lighthouse make-example`.

usage: /usr/bin/python3 read_our_file.py /path/to/lighthouse

Checks grid names, types, grid class, vector type, `level` and domain metadata, the file
metadata (format version, layout, reference camera), each level's transform against the
layout of docs/conventions.md#nested-volume-layout (voxel (0,0,0) centred at box.min + voxel/2, voxel size s0/2^k/R),
the voxel values, and that OpenVDB's own `vdb_print` lists every grid (skipped if absent).
"""

import json
import math
import os
import shutil
import sys
import tempfile

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import lh_testlib as lt  # noqa: E402

vdb, np = lt.import_openvdb()
LEVELS, RES, S0 = 3, 16, 14.0


def box(level):
    """World box of a level (docs/conventions.md#nested-volume-layout)."""
    s = S0 / 2 ** level
    if level == 0:
        return (-s / 2, -s / 2, -s / 2), (s / 2, s / 2, s / 2)
    return (-s / 2, -s / 2, 0.0), (s / 2, s / 2, s)


def main():
    lighthouse = lt.lighthouse_from_argv()
    t = lt.Checks("read_our_file")
    with tempfile.TemporaryDirectory(prefix="lh_read_our_file_") as tmp:
        path = os.path.join(tmp, "f.vdb")
        p = lt.run([lighthouse, "make-example", "--levels", LEVELS, "--res", RES, "-o", path])
        if not t.check(p.returncode == 0 and os.path.isfile(path),
                       "lighthouse make-example failed: " + lt.describe(p)):
            t.finish()

        # ---- Grid metadata, without loading voxels.
        metas = vdb.readAllGridMetadata(path)
        names = sorted(g.name for g in metas)
        expected = sorted(["density_L%d" % k for k in range(LEVELS)] +
                          ["color_L%d" % k for k in range(LEVELS)])
        t.equal(names, expected, "grid names")
        for g in metas:
            kind, _, suffix = g.name.partition("_L")
            if not suffix.isdigit():
                continue
            k = int(suffix)
            if kind == "density":
                t.check(isinstance(g, vdb.FloatGrid),
                        "%s is a %s, expected FloatGrid" % (g.name, type(g).__name__))
                t.equal(g.gridClass, vdb.GridClass.FOG_VOLUME, "%s grid class" % g.name)
            elif kind == "color":
                t.check(isinstance(g, vdb.Vec3SGrid),
                        "%s is a %s, expected Vec3SGrid" % (g.name, type(g).__name__))
                t.equal(g.vectorType, vdb.VectorType.INVARIANT, "%s vector type" % g.name)
            t.check("level" in g, "%s has no 'level' metadata" % g.name) and \
                t.equal(g["level"], k, "%s 'level' metadata" % g.name)
            for key, value in (("lighthouse_domain_min", (0, 0, 0)),
                               ("lighthouse_domain_max", (RES - 1,) * 3)):
                t.check(key in g, "%s has no '%s' metadata" % (g.name, key)) and \
                    t.equal(tuple(g[key]), value, "%s '%s'" % (g.name, key))

        # ---- Everything, with the file metadata.
        grids, file_meta = vdb.readAll(path)
        t.equal(file_meta.get("lighthouse_format_version"), 1, "lighthouse_format_version")
        layout_text = file_meta.get("lighthouse_layout")
        if t.check(isinstance(layout_text, str), "lighthouse_layout is missing or not a string: %r"
                   % (layout_text,)):
            try:
                layout = json.loads(layout_text)
            except ValueError as e:
                layout = None
                t.check(False, "lighthouse_layout is not JSON (%s): %r" % (e, layout_text))
            if layout is not None:
                t.equal(layout.get("s0"), S0, "layout s0")
                t.equal(layout.get("levels"), LEVELS, "layout levels")
                t.equal(layout.get("resolution"), RES, "layout resolution")
        cam_text = file_meta.get("lighthouse_ref_camera")
        if t.check(isinstance(cam_text, str), "lighthouse_ref_camera is missing"):
            try:
                cam = json.loads(cam_text)
                for key in ("width", "height", "fx", "fy", "cx", "cy", "cam_to_world"):
                    t.check(key in cam, "lighthouse_ref_camera has no '%s'" % key)
            except ValueError as e:
                t.check(False, "lighthouse_ref_camera is not JSON (%s)" % e)

        by_name = {g.name: g for g in grids}
        for k in range(LEVELS):
            density = by_name.get("density_L%d" % k)
            color = by_name.get("color_L%d" % k)
            if not t.check(density is not None and color is not None, "level %d grids missing" % k):
                continue
            voxel = S0 / 2 ** k / RES
            lo, hi = box(k)
            first = tuple(c + voxel / 2 for c in lo)
            last = tuple(c - voxel / 2 for c in hi)
            for g in (density, color):
                xf = g.transform
                t.check(xf.isLinear, "%s transform is not linear" % g.name)
                t.close(xf.voxelSize(), (voxel,) * 3, "%s voxel size" % g.name)
                t.close(xf.indexToWorld((0, 0, 0)), first,
                        "%s index (0,0,0) -> world (box.min + voxel/2)" % g.name)
                t.close(xf.indexToWorld((RES - 1,) * 3), last,
                        "%s index (R-1,R-1,R-1) -> world (box.max - voxel/2)" % g.name)
                t.close(xf.worldToIndex(lo), (-0.5,) * 3, "%s box.min -> index" % g.name)
            # Values: finite, non-negative density; colour finite and non-negative.
            dens = np.zeros((RES, RES, RES), dtype=np.float32)
            density.copyToArray(dens, ijk=(0, 0, 0))
            col = np.zeros((RES, RES, RES, 3), dtype=np.float32)
            color.copyToArray(col, ijk=(0, 0, 0))
            t.check(np.all(np.isfinite(dens)) and np.all(dens >= 0),
                    "density_L%d holds non-finite or negative values" % k)
            t.check(np.all(np.isfinite(col)) and np.all(col >= 0),
                    "color_L%d holds non-finite or negative values" % k)
            t.check(density.activeVoxelCount() > 0 and dens.max() > 0,
                    "density_L%d is empty" % k)
            t.equal(density.activeVoxelCount(), color.activeVoxelCount(),
                    "active voxels of density_L%d vs color_L%d" % (k, k))
            bmin, bmax = density.evalActiveVoxelBoundingBox()
            t.check(all(0 <= c < RES for c in tuple(bmin) + tuple(bmax)),
                    "density_L%d active voxels %r..%r outside the %d^3 domain"
                    % (k, bmin, bmax, RES))

        # ---- OpenVDB's own tool.
        vdb_print = shutil.which("vdb_print") or (
            "/usr/bin/vdb_print" if os.access("/usr/bin/vdb_print", os.X_OK) else None)
        if vdb_print is None:
            print("note: vdb_print not found (libopenvdb-tools); skipping that part")
        else:
            p = lt.run([vdb_print, path])
            if t.check(p.returncode == 0, "vdb_print failed: " + lt.describe(p)):
                listed = sorted(line.split()[0] for line in p.stdout.splitlines() if line.strip())
                t.equal(listed, expected, "grids listed by vdb_print")
            p = lt.run([vdb_print, "-l", path])
            if t.check(p.returncode == 0, "vdb_print -l failed: " + lt.describe(p)):
                t.check("lighthouse_layout" in p.stdout,
                        "vdb_print -l does not show the lighthouse_layout metadata")
    t.finish()


if __name__ == "__main__":
    main()
