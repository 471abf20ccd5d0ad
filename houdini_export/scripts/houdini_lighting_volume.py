"""Load a lighthouse export into Houdini with an equivalent emission-absorption volume shader.

NOT TESTED HERE: Houdini is not installed on the machines this project is built and tested on.
Its conventions (names, types, vector types, Y-up transforms) are tested with python3-openvdb
in tests/python/dcc_conventions.py instead; this script follows Houdini 19.5/20's Python API
(hou) as documented, and should be treated as a starting point.

Run it with hython (or paste into Houdini's Python Shell and call main([...])):

  hython houdini_lighting_volume.py --export EXPORT_DIR [--save scene.hip]

EXPORT_DIR is what `lighthouse export VOLUME.vdb --for houdini -o EXPORT_DIR` wrote: one
`level_<k>.vdb` per level (non-overlapping shells: Karma and Mantra add overlapping volumes)
and manifest.json. Each file holds VDB primitives
  density   float, fog volume: extinction sigma, per metre (per Houdini unit)
  emission  vector, "Tuple/Color": sigma * radiance (premultiplied, what the shader emits)
  Cd        vector, "Tuple/Color": radiance (for display and for lighthouse import)
already in Houdini's axes (Y-up: X = x, Y = -y, Z = -z of lighthouse's OpenCV frame, so the
reference camera looks down Houdini's -Z like a default Houdini camera). No transform is needed.

The script builds /obj/lighthouse_volume: one File SOP per level, a Merge, and a Karma
MaterialX material
  absorption coefficient = density           (mtlxabsorption_vdf, absorption colour 1)
  emission               = emission          (mtlxuniform_edf, colour from the field)
with no scattering, so Karma integrates L = int T(t) sigma(t) colour(t) dt as lighthouse does.
Render an envmap with a spherical (lat-long) Karma camera at Houdini (x, -y, -z) of the
lighthouse point; lighthouse's envmap centre column looks along Houdini -Z, row 0 along +Y.
"""

import argparse
import json
import os
import sys


def parse_args(argv):
    p = argparse.ArgumentParser(prog="houdini_lighting_volume")
    p.add_argument("--export", required=True, help="export directory (lighthouse export --for houdini)")
    p.add_argument("--save", help="save the scene to this .hip file")
    return p.parse_args(argv)


def read_manifest(export_dir):
    path = os.path.join(export_dir, "manifest.json")
    if not os.path.isfile(path):
        raise ValueError("'%s' is not a lighthouse export: no manifest.json" % export_dir)
    with open(path) as f:
        manifest = json.load(f)
    if manifest.get("for") != "houdini":
        raise ValueError("'%s' was exported for '%s', not for houdini" % (export_dir, manifest.get("for")))
    return manifest


def build_geometry(hou, export_dir, manifest):
    obj = hou.node("/obj").createNode("geo", "lighthouse_volume")
    for child in obj.children():
        child.destroy()
    merge = obj.createNode("merge", "levels")
    for k, level in enumerate(manifest["levels"]):
        f = obj.createNode("file", "level_%d" % k)
        f.parm("file").set(os.path.abspath(os.path.join(export_dir, level["file"])))
        merge.setInput(k, f)
    return obj, merge


def build_material(hou):
    """Karma MaterialX volume: absorption from `density`, emission from `emission`."""
    mat = hou.node("/mat").createNode("subnet", "lighthouse_emission_absorption")
    density = mat.createNode("mtlxgeompropvalue", "density")
    density.parm("signature").set("float")
    density.parm("geomprop").set("density")
    emission = mat.createNode("mtlxgeompropvalue", "emission")
    emission.parm("signature").set("color3")
    emission.parm("geomprop").set("emission")
    absorb = mat.createNode("mtlxabsorption_vdf", "absorption")
    absorb.setNamedInput("absorption", density, 0)
    emit = mat.createNode("mtlxuniform_edf", "emit")
    emit.setNamedInput("color", emission, 0)
    volume = mat.createNode("mtlxvolume", "volume")
    volume.setNamedInput("vdf", absorb, 0)
    volume.setNamedInput("edf", emit, 0)
    out = mat.createNode("subnetconnector", "volume_output")
    out.parm("connectorkind").set("output")
    out.parm("parmname").set("volume")
    out.parm("parmtype").set("volume")
    out.setInput(0, volume)
    mat.layoutChildren()
    return mat


def main(argv):
    args = parse_args(argv)
    try:
        import hou  # noqa: F401  (only inside Houdini / hython)
    except ImportError:
        print("houdini_lighting_volume: error: run this with hython or inside Houdini (no 'hou' module)",
              file=sys.stderr)
        return 1
    manifest = read_manifest(args.export)
    obj, merge = build_geometry(hou, args.export, manifest)
    mat = build_material(hou)
    assign = obj.createNode("material", "assign")
    assign.setInput(0, merge)
    assign.parm("shop_materialpath1").set(mat.path())
    assign.setDisplayFlag(True)
    assign.setRenderFlag(True)
    obj.layoutChildren()
    if args.save:
        hou.hipFile.save(os.path.abspath(args.save))
    print("houdini_lighting_volume: loaded %d level(s) from %s" % (len(manifest["levels"]), args.export))
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except (ValueError, OSError) as e:
        print("houdini_lighting_volume: error: %s" % e, file=sys.stderr)
        sys.exit(1)
