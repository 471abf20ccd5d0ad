"""Load a lighthouse export into Blender and render or save it.

Run it with Blender (3.4 or later), never with a plain python:

  blender -b --factory-startup --python blender_lighting_volume.py -- \
      --export EXPORT_DIR [--save-blend scene.blend] \
      [--envmap env.exr|env.png --at X,Y,Z [--size 64x32] [--samples 32]]

EXPORT_DIR is what `lighthouse export VOLUME.vdb --for blender -o EXPORT_DIR` wrote: one
`level_<k>.vdb` per level (non-overlapping shells) and `manifest.json`. Each level becomes a
Volume object sharing one emission-absorption material:

  absorption coefficient = density                    (Volume Absorption, colour black)
  emission coefficient   = density * colour            (Emission, strength 1; per metre)
                           from the float grids emission_r, emission_g, emission_b

so Cycles integrates L = int T(t) sigma(t) colour(t) dt exactly as lighthouse does, with the
premultiplied emission interpolated (docs/conventions.md#interpolation). There is no scattering. Overlapping
volume objects add up in Cycles, which is why the export holds shells, not nested levels.

--at is a point in LIGHTHOUSE's world frame (the reference camera's OpenCV frame: x right,
y down, z forward); the script converts it with the manifest's axes (Blender X = x, Y = z,
Z = -y) and points the equirectangular camera so that the picture follows lighthouse's envmap
layout: row 0 looks up, the centre column looks forward (+z, Blender +Y), column 3W/4 looks
right (+x, Blender +X). .exr output is linear radiance; .png is sRGB ("Standard" view).
With --save-blend the scene (volumes, material, and the camera if --at is given) is saved.

Exit status: 0 on success, 1 with one "error:" line on bad input.
"""

import json
import math
import os
import sys

import bpy

PROG = "blender_lighting_volume"
EMISSION_GRIDS = ("emission_r", "emission_g", "emission_b")


class UsageError(Exception):
    pass


def parse_args(argv):
    import argparse

    class Parser(argparse.ArgumentParser):
        def error(self, message):
            raise UsageError(message)

    p = Parser(prog=PROG, description="Load a lighthouse export into Blender.")
    p.add_argument("--export", required=True, help="export directory (lighthouse export --for blender)")
    p.add_argument("--save-blend", help="save the scene to this .blend file")
    p.add_argument("--envmap", help="render an equirectangular envmap to this .exr or .png")
    p.add_argument("--at", help="envmap position X,Y,Z in lighthouse's world frame (metres)")
    p.add_argument("--size", default="64x32", help="envmap size WxH with W = 2H (default 64x32)")
    p.add_argument("--samples", type=int, default=32, help="Cycles samples per pixel (default 32)")
    p.add_argument("--step-rate", type=float, default=0.5,
                   help="Cycles volume step, in voxels of each level (default 0.5)")
    p.add_argument("--filter-width", type=float, default=0.01,
                   help="pixel filter width in pixels; 0.01 samples pixel centres as lighthouse "
                        "does (Blender's default is 1.5)")
    p.add_argument("--threads", type=int, default=0, help="render threads (0 = all cores)")
    p.add_argument("--half", action="store_true",
                   help="keep Blender's default half-precision volume grids (default: full)")
    args = p.parse_args(argv)
    if not args.envmap and not args.save_blend:
        raise UsageError("nothing to do: give --envmap and/or --save-blend")
    if args.envmap and not args.at:
        raise UsageError("--envmap needs --at X,Y,Z")
    if args.envmap and os.path.splitext(args.envmap)[1].lower() not in (".exr", ".png"):
        raise UsageError("--envmap must end in .exr or .png, got '%s'" % args.envmap)
    if args.samples < 1:
        raise UsageError("--samples must be at least 1")
    if not (args.step_rate > 0) or not math.isfinite(args.step_rate):
        raise UsageError("--step-rate must be positive")
    try:
        w, h = (int(v) for v in args.size.lower().split("x"))
    except ValueError:
        raise UsageError("--size: expected WxH, got '%s'" % args.size)
    if w < 2 or w != 2 * h:
        raise UsageError("--size: need W = 2 H >= 2, got '%s'" % args.size)
    args.width, args.height = w, h
    if args.at:
        try:
            at = [float(v) for v in args.at.split(",")]
        except ValueError:
            raise UsageError("--at: expected X,Y,Z, got '%s'" % args.at)
        if len(at) != 3 or not all(math.isfinite(v) for v in at):
            raise UsageError("--at: expected three finite numbers, got '%s'" % args.at)
        args.at = at
    return args


def read_manifest(export_dir):
    path = os.path.join(export_dir, "manifest.json")
    if not os.path.isdir(export_dir):
        raise UsageError("'%s' is not a directory (run lighthouse export first)" % export_dir)
    if not os.path.isfile(path):
        raise UsageError("'%s' is not a lighthouse export: no manifest.json" % export_dir)
    try:
        with open(path) as f:
            manifest = json.load(f)
    except ValueError as e:
        raise UsageError("'%s' is not valid JSON (%s)" % (path, e))
    if manifest.get("for") != "blender":
        raise UsageError("'%s' was exported for '%s', not for blender (use --for blender)"
                         % (export_dir, manifest.get("for")))
    return manifest


def to_blender(manifest, p):
    """Lighthouse world point -> Blender world point (manifest's world_to_dcc rotation)."""
    r = manifest["world_to_dcc"]
    return tuple(sum(r[i][j] * p[j] for j in range(3)) for i in range(3))


def make_material():
    """Emission-absorption: density absorbs, premultiplied `emission` emits, no scattering."""
    mat = bpy.data.materials.new("lighthouse_emission_absorption")
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    nodes.clear()
    out = nodes.new("ShaderNodeOutputMaterial")
    density = nodes.new("ShaderNodeAttribute")
    density.attribute_name = "density"
    # Premultiplied emission arrives as three float grids: Blender 3.4's Cycles misreads Vec3
    # grids through the Attribute node (houdini_export/README.md), float grids are exact.
    combine = nodes.new("ShaderNodeCombineXYZ")
    for axis, name in zip("XYZ", EMISSION_GRIDS):
        channel = nodes.new("ShaderNodeAttribute")
        channel.attribute_name = name
        links.new(channel.outputs["Fac"], combine.inputs[axis])
    absorb = nodes.new("ShaderNodeVolumeAbsorption")
    absorb.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)  # coefficient = (1 - colour) * density
    emit = nodes.new("ShaderNodeEmission")
    emit.inputs["Strength"].default_value = 1.0  # emission coefficient = colour, per metre
    add = nodes.new("ShaderNodeAddShader")
    links.new(density.outputs["Fac"], absorb.inputs["Density"])
    links.new(combine.outputs["Vector"], emit.inputs["Color"])
    links.new(absorb.outputs["Volume"], add.inputs[0])
    links.new(emit.outputs["Emission"], add.inputs[1])
    links.new(add.outputs["Shader"], out.inputs["Volume"])
    return mat


def load_levels(export_dir, manifest, material, half):
    objects = []
    for k, level in enumerate(manifest.get("levels", [])):
        path = os.path.abspath(os.path.join(export_dir, level["file"]))
        if not os.path.isfile(path):
            raise UsageError("'%s' is missing from the export" % path)
        vol = bpy.data.volumes.new("lighthouse_level_%d" % k)
        vol.filepath = path
        if not vol.grids.load():
            raise UsageError("Blender cannot read '%s': %s" % (path, vol.grids.error_message))
        names = {g.name for g in vol.grids}
        for need in ("density",) + EMISSION_GRIDS:
            if need not in names:
                raise UsageError("'%s' has no '%s' grid (grids: %s)" % (path, need, sorted(names)))
        vol.render.precision = "HALF" if half else "FULL"
        vol.render.space = "OBJECT"
        vol.render.step_size = 0.0  # automatic: one voxel of this level, times the step rate
        vol.materials.append(material)
        obj = bpy.data.objects.new("lighthouse_level_%d" % k, vol)
        bpy.context.scene.collection.objects.link(obj)
        objects.append(obj)
    if not objects:
        raise UsageError("the manifest lists no levels")
    return objects


def setup_scene(args):
    scene = bpy.context.scene
    for obj in list(scene.collection.all_objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = args.samples
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.use_denoising = False  # Debian's Blender has no OpenImageDenoise
    scene.cycles.seed = 0
    scene.cycles.pixel_filter_type = "BOX"
    scene.cycles.filter_width = args.filter_width
    scene.cycles.max_bounces = 0  # no scattering: camera rays see emission and absorption only
    scene.cycles.volume_bounces = 0
    scene.cycles.volume_step_rate = args.step_rate
    scene.cycles.volume_max_steps = 4096
    if args.threads > 0:
        scene.render.threads_mode = "FIXED"
        scene.render.threads = args.threads
    world = bpy.data.worlds.new("lighthouse_black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    scene.world = world
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    scene.render.resolution_x = args.width
    scene.render.resolution_y = args.height
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = False
    return scene


def add_envmap_camera(scene, manifest, at):
    cam = bpy.data.cameras.new("lighthouse_envmap")
    cam.type = "PANO"
    cam.cycles.panorama_type = "EQUIRECTANGULAR"
    cam.cycles.longitude_min, cam.cycles.longitude_max = -math.pi, math.pi
    cam.cycles.latitude_min, cam.cycles.latitude_max = -math.pi / 2, math.pi / 2
    cam.clip_start = 1e-5  # metres: the default 0.1 would cut the volume around the point
    cam.clip_end = 1e6     # the default 100 would cut a large room's coarse level
    obj = bpy.data.objects.new("lighthouse_envmap", cam)
    obj.location = to_blender(manifest, at)
    # Camera looks along its -Z with +Y up; rotating +90 degrees about X makes it look along
    # Blender +Y (lighthouse +z, the envmap's centre column) with Blender +Z (lighthouse -y)
    # up. This assumes the Blender export axes; checked by tests/python/dcc_blender_cycles.py.
    obj.rotation_euler = (math.pi / 2, 0.0, 0.0)
    scene.collection.objects.link(obj)
    scene.camera = obj
    return obj


def render_envmap(scene, path):
    ext = os.path.splitext(path)[1].lower()
    settings = scene.render.image_settings
    if ext == ".exr":
        settings.file_format = "OPEN_EXR"
        settings.color_depth = "32"
        settings.exr_codec = "ZIP"
    else:
        settings.file_format = "PNG"
        settings.color_depth = "8"
    settings.color_mode = "RGB"
    out_dir = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(out_dir):
        raise UsageError("cannot write '%s': directory '%s' does not exist" % (path, out_dir))
    tmp = os.path.join(out_dir, ".%s.tmp%d%s" % (os.path.basename(path), os.getpid(), ext))
    scene.render.filepath = tmp
    scene.render.use_file_extension = False
    bpy.ops.render.render(write_still=True)
    if not os.path.isfile(tmp):
        raise UsageError("Blender did not write '%s'" % path)
    os.replace(tmp, path)  # never a half-written file under the final name


def save_blend(path):
    out_dir = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(out_dir):
        raise UsageError("cannot write '%s': directory '%s' does not exist" % (path, out_dir))
    tmp = os.path.join(out_dir, ".%s.tmp%d.blend" % (os.path.basename(path), os.getpid()))
    bpy.ops.wm.save_as_mainfile(filepath=tmp, check_existing=False, copy=True)
    os.replace(tmp, path)


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    args = parse_args(argv)
    manifest = read_manifest(args.export)
    scene = setup_scene(args)
    load_levels(args.export, manifest, make_material(), args.half)
    if args.at:
        add_envmap_camera(scene, manifest, args.at)
    if args.envmap:
        render_envmap(scene, args.envmap)
        print("%s: wrote %s" % (PROG, args.envmap))
    if args.save_blend:
        save_blend(args.save_blend)
        print("%s: wrote %s" % (PROG, args.save_blend))


if __name__ == "__main__":
    try:
        main()
    except UsageError as e:
        print("%s: error: %s" % (PROG, e), file=sys.stderr)
        sys.stdout.flush()
        sys.stderr.flush()
        sys.exit(1)
    except Exception as e:  # anything else: still one line and a non-zero exit
        print("%s: error: %s: %s" % (PROG, type(e).__name__, e), file=sys.stderr)
        sys.stdout.flush()
        sys.stderr.flush()
        sys.exit(1)
    sys.exit(0)
