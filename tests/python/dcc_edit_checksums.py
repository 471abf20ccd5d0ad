#!/usr/bin/python3
"""Edits made with python3-openvdb to either radiance grid of an export come back through
`lighthouse import`, and an MPI goes out with `export` and comes back.

usage: /usr/bin/python3 dcc_edit_checksums.py /path/to/lighthouse

The example room (3 levels of 16^3) is exported; one voxel of level_0.vdb (its first with
density above 0.5) is edited, the export imported, and that voxel of `color_L0` in the imported
file checked:
  * `Cd` (Houdini) or `color` (Blender) set to (0.25, 0.5, 2): the voxel reads exactly that,
    and import's output names the edited grid;
  * the emission grid(s) set to density x (3, 0, 0.5): the voxel reads (3, 0, 0.5);
  * `Cd` set to (0, 0, 3) and `emission` to density x (3, 0, 0): emission wins, and one
    `warning:` line names level 0, its file and both grids;
  * the manifest's checksums removed (an older export): the `Cd` edit is ignored, with one
    warning saying so;
  * the manifest's checksum of one grid not 16 hex digits: one `lighthouse: error:` line,
    exit 1, no output.
An MPI of 2 planes added to the room with python3-openvdb is written by export as mpi.vdb and
is in the imported file again: grid names, metadata and the values of one pixel.
"""

import json
import os
import shutil
import sys
import tempfile

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import lh_testlib as lt  # noqa: E402

vdb, np = lt.import_openvdb()

EMISSION = ("emission_r", "emission_g", "emission_b")


def read(path):
    grids, meta = vdb.readAll(path)
    return {g.name: g for g in grids}, grids, meta


def first_voxel(level_file):
    g, _, _ = read(level_file)
    for item in g["density"].iterOnValues():
        if item["value"] > 0.5 and item["min"] == item["max"]:
            return item["min"], item["value"]
    raise RuntimeError("no voxel with density in " + level_file)


def edit(level_file, fn):
    g, grids, meta = read(level_file)
    fn(g)
    vdb.write(level_file, grids=grids, metadata=meta)


def set_emission(g, program, ijk, value):
    if program == "blender":
        for c, name in enumerate(EMISSION):
            g[name].getAccessor().setValueOn(ijk, value[c])
    else:
        g["emission"].getAccessor().setValueOn(ijk, value)


def colour_grid(program):
    return "color" if program == "blender" else "Cd"


def main():
    lighthouse = lt.lighthouse_from_argv()
    t = lt.Checks("dcc_edit_checksums")
    with tempfile.TemporaryDirectory(prefix="lh_dcc_checksums_") as tmp:
        room = os.path.join(tmp, "room.vdb")
        p = lt.run([lighthouse, "make-example", "--levels", "3", "--res", "16", "-o", room])
        if not t.check(p.returncode == 0, "make-example failed: " + lt.describe(p)):
            t.finish()

        def export(program, name, source=room):
            out = os.path.join(tmp, name)
            p = lt.run([lighthouse, "export", source, "--for", program, "-o", out])
            t.check(p.returncode == 0, "export %s failed: %s" % (name, lt.describe(p)))
            return out, p

        def import_back(program, exp):
            out = exp + ".vdb"
            p = lt.run([lighthouse, "import", exp, "--from", program, "-o", out])
            return out, p

        def imported_colour(path, ijk):
            g, _, _ = read(path)
            return g["color_L0"].getAccessor().getValue(ijk)

        def warnings(p):
            return [line for line in p.stderr.splitlines() if line.startswith("warning:")]

        for program in ("houdini", "blender"):
            cd = colour_grid(program)
            # The colour grid edited.
            exp, _ = export(program, program + "_colour")
            ijk, sigma = first_voxel(os.path.join(exp, "level_0.vdb"))
            edit(os.path.join(exp, "level_0.vdb"), lambda g: g[cd].getAccessor().setValueOn(ijk, (0.25, 0.5, 2.0)))
            out, p = import_back(program, exp)
            if t.check(p.returncode == 0, "import of an edited %s failed: %s" % (cd, lt.describe(p))):
                t.close(imported_colour(out, ijk), (0.25, 0.5, 2.0), "%s: imported colour after editing '%s'"
                        % (program, cd), 1e-7)
                t.check("'%s' was edited" % cd in p.stdout, "%s: import does not say that '%s' was edited: %s"
                        % (program, cd, p.stdout))
                t.equal(warnings(p), [], "%s: warnings after a colour edit" % program)
            # The emission grid(s) edited.
            exp, _ = export(program, program + "_emission")
            edit(os.path.join(exp, "level_0.vdb"),
                 lambda g: set_emission(g, program, ijk, (3.0 * sigma, 0.0, 0.5 * sigma)))
            out, p = import_back(program, exp)
            if t.check(p.returncode == 0, "import of an edited emission failed: " + lt.describe(p)):
                t.close(imported_colour(out, ijk), (3.0, 0.0, 0.5), "%s: imported colour after editing emission"
                        % program, 1e-5)

        # Both edited, disagreeing (Houdini).
        exp, _ = export("houdini", "both")

        def both(g):
            g["Cd"].getAccessor().setValueOn(ijk, (0.0, 0.0, 3.0))
            g["emission"].getAccessor().setValueOn(ijk, (3.0 * sigma, 0.0, 0.0))
        edit(os.path.join(exp, "level_0.vdb"), both)
        out, p = import_back("houdini", exp)
        if t.check(p.returncode == 0, "import with both grids edited failed: " + lt.describe(p)):
            t.close(imported_colour(out, ijk), (3.0, 0.0, 0.0), "both edited: emission wins", 1e-5)
            w = warnings(p)
            t.check(len(w) == 1 and "level_0.vdb' (level 0): both 'Cd' and 'emission' were edited" in w[0]
                    and "disagree in 1 voxel(s)" in w[0], "both edited: expected one warning, got %r" % w)

        # No checksums: today's rule, said once.
        exp, _ = export("houdini", "old")
        manifest_path = os.path.join(exp, "manifest.json")
        with open(manifest_path) as f:
            manifest = json.load(f)
        original = imported_colour(import_back("houdini", exp)[0], ijk)
        manifest.pop("checksum", None)
        for level in manifest["levels"]:
            level.pop("checksums", None)
        with open(manifest_path, "w") as f:
            json.dump(manifest, f)
        edit(os.path.join(exp, "level_0.vdb"), lambda g: g["Cd"].getAccessor().setValueOn(ijk, (9.0, 9.0, 9.0)))
        out, p = import_back("houdini", exp)
        if t.check(p.returncode == 0, "import without checksums failed: " + lt.describe(p)):
            t.close(imported_colour(out, ijk), original, "no checksums: the Cd edit is ignored", 1e-5)
            w = warnings(p)
            t.check(len(w) == 1 and "has no grid checksums" in w[0], "no checksums: expected one warning, got %r" % w)

        # A corrupt checksum: one error line, nothing written.
        exp, _ = export("houdini", "corrupt")
        manifest_path = os.path.join(exp, "manifest.json")
        with open(manifest_path) as f:
            manifest = json.load(f)
        manifest["levels"][0]["checksums"]["Cd"] = "zz"
        with open(manifest_path, "w") as f:
            json.dump(manifest, f)
        out, p = import_back("houdini", exp)
        t.equal(p.returncode, 1, "corrupt checksum: exit code")
        lines = p.stderr.strip().splitlines()
        t.check(len(lines) == 1 and lines[0].startswith("lighthouse: error: ") and "level 0's \"checksums\"" in lines[0],
                "corrupt checksum: expected one error line, got %r" % lines)
        t.check(not os.path.exists(out), "corrupt checksum: %s was written" % out)

        # The MPI: added to the room by hand, through export and import.
        grids, meta = vdb.readAll(room)
        for d in range(2):
            alpha = vdb.FloatGrid()
            alpha.name = "mpi_alpha_P%02d" % d
            rgb = vdb.Vec3SGrid()
            rgb.name = "mpi_rgb_P%02d" % d
            for g in (alpha, rgb):
                g["mpi_plane"] = d
                g["mpi_depth"] = 2.0 + d
            alpha.getAccessor().setValueOn((30, 40, 0), 0.25 + 0.5 * d)
            rgb.getAccessor().setValueOn((30, 40, 0), (1.0, 2.0, 3.0 + d))
            grids += [alpha, rgb]
        meta["lighthouse_mpi_camera"] = meta["lighthouse_ref_camera"]
        room_mpi = os.path.join(tmp, "room_mpi.vdb")
        vdb.write(room_mpi, grids=grids, metadata=meta)
        exp, p = export("houdini", "mpi", room_mpi)
        t.check("mpi.vdb: the MPI, 2 plane(s)" in p.stdout, "export does not list the MPI: " + p.stdout)
        t.check(os.path.isfile(os.path.join(exp, "mpi.vdb")), "export wrote no mpi.vdb")
        out, p = import_back("houdini", exp)
        if t.check(p.returncode == 0, "import with an MPI failed: " + lt.describe(p)):
            t.check("and the MPI (2 plane(s)" in p.stdout, "import does not mention the MPI: " + p.stdout)
            g, _, meta = read(out)
            t.check("lighthouse_mpi_camera" in meta, "the imported file has no lighthouse_mpi_camera")
            for d in range(2):
                for name in ("mpi_alpha_P%02d" % d, "mpi_rgb_P%02d" % d):
                    if not t.check(name in g, "the imported file has no grid %s (it has %s)" % (name, sorted(g))):
                        continue
                    t.equal(g[name]["mpi_plane"], d, name + " mpi_plane")
                    t.equal(g[name]["mpi_depth"], 2.0 + d, name + " mpi_depth")
                if "mpi_alpha_P%02d" % d in g and "mpi_rgb_P%02d" % d in g:
                    t.equal(g["mpi_alpha_P%02d" % d].getAccessor().getValue((30, 40, 0)), 0.25 + 0.5 * d,
                            "plane %d alpha at pixel (30, 40)" % d)
                    t.close(g["mpi_rgb_P%02d" % d].getAccessor().getValue((30, 40, 0)), (1.0, 2.0, 3.0 + d),
                            "plane %d rgb at pixel (30, 40)" % d)
        shutil.rmtree(exp, ignore_errors=True)
    t.finish()


if __name__ == "__main__":
    main()
