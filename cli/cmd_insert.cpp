// `lighthouse insert V.vdb --image ref.png --cameras cameras.json --object sphere
//  --at X,Y,Z [--scale S] [--rotate RX,RY,RZ] --material mirror [--object ...] -o OUT.png`
#include "cli/cli_common.h"
#include "cli/commands.h"
#include "cli/common_options.h"
#include "core/atomic_file.h"
#include "core/errors.h"
#include "core/path_guard.h"
#include "image/contact_sheet.h"
#include "image/image_io.h"
#include "image/resample.h"
#include "insert/insertion.h"
#include "render/envmap.h"

#include <chrono>
#include <iostream>

namespace lh::cli {

namespace {

struct InsertCommandOptions {
    std::string volume, image, cameras, view = "ref", output;
    std::vector<std::string> objects, at, scales, rotations, materials;
    std::string path;
    InsertOptions insert;
    bool noShadows = false;
    bool alsoPng = false;
    float exposure = 1.f;
    bool strict = false;
};

// The i-th of a per-object option given 0 times (default), once (for all) or once per object.
template <typename T>
T perObject(const std::vector<T>& values, std::size_t i, const T& fallback, const char* name,
            std::size_t count) {
    if (values.empty()) return fallback;
    if (values.size() == 1) return values[0];
    if (values.size() != count)
        throw InputError(std::string(name) + " is given " + std::to_string(values.size()) +
                         " times for " + std::to_string(count) +
                         " objects: give it once (for all) or once per object");
    return values[i];
}

std::vector<InsertedObject> buildObjects(const InsertCommandOptions& o) {
    if (o.objects.empty())
        throw InputError(
            "give at least one --object (sphere, cube, torus, cylinder or an .obj file)");
    if (o.at.size() != o.objects.size())
        throw InputError("each --object needs its own --at X,Y,Z (" +
                         std::to_string(o.objects.size()) + " objects, " +
                         std::to_string(o.at.size()) + " positions)");
    std::vector<InsertedObject> objects;
    for (std::size_t i = 0; i < o.objects.size(); ++i) {
        const double scale =
            std::stod(perObject<std::string>(o.scales, i, "0.2", "--scale", o.objects.size()));
        const Vec3d rotation = parsePoint(
            perObject<std::string>(o.rotations, i, "0,0,0", "--rotate", o.objects.size()),
            "--rotate");
        const Material material = Material::parse(
            perObject<std::string>(o.materials, i, "mirror", "--material", o.objects.size()));
        objects.push_back(placeObject(loadMesh(o.objects[i]), material, parsePoint(o.at[i], "--at"),
                                      scale, rotationFromDegrees(rotation)));
    }
    return objects;
}

// One warning per inserted object that the photo will not show, naming it and saying why.
void warnOfHiddenObjects(const InsertCommandOptions& o, const std::vector<InsertedObject>& objects,
                         const PinholeCamera& camera,
                         const std::vector<ObjectVisibility>& visibility) {
    for (std::size_t i = 0; i < objects.size(); ++i) {
        const std::string why = hiddenReason(objects[i], camera, visibility[i]);
        if (!why.empty())
            std::cerr << "warning: object " << i + 1 << " (" << o.objects[i] << " at " << o.at[i]
                      << ") is not visible in the image: " << why << "\n";
    }
}

void writeOutput(const ImageRGB& image, const std::string& path, const InsertCommandOptions& o) {
    writeImage(image, path, o.exposure);
    if (o.alsoPng && fileExtension(path) == ".exr")
        writePng(image, withExtension(path, ".png"), o.exposure);
}

void runInsert(const InsertCommandOptions& o) {
    const std::string ext = fileExtension(o.output);
    if (ext != ".exr" && ext != ".png")
        throw InputError("output '" + o.output + "' must end in .exr or .png");
    requirePositiveExposure(o.exposure);
    std::vector<NamedInput> inputs = {{o.volume, "the input volume"},
                                      {o.image, "--image"},
                                      {o.cameras, "--cameras"},
                                      {o.path, "--path"}};
    for (const auto& object : o.objects) inputs.push_back({object, "--object"});
    requireOutputIsNotAnInput(o.output, "-o", inputs);
    if (o.alsoPng) requireOutputIsNotAnInput(withExtension(o.output, ".png"), "--png", inputs);
    if (!o.path.empty()) {
        requireOutputIsNotAnInput(withExtension(o.output, "") + "_sheet.png", "the contact sheet",
                                  inputs);
        requireOutputIsNotAnInput(withExtension(o.output, "") + "_epipolar.png",
                                  "the epipolar image", inputs);
    }
    for (const auto& s : o.scales) try {
            if (!(std::stod(s) > 0)) throw std::invalid_argument("scale");
        } catch (const std::exception&) {
            throw InputError("--scale must be a positive number, got '" + s + "'");
        }
    InsertOptions options = o.insert;
    options.shadows = !o.noShadows;
    options.validate();
    std::vector<InsertedObject> objects = buildObjects(o);
    const CamerasFile cameras = loadCamerasFile(o.cameras);
    const PinholeCamera& camera = cameras.view(o.view);
    const ImageRGB photo = readImage(o.image);
    const RenderVolume volume(loadVolumeForCli(o.volume, o.strict));

    if (o.path.empty()) {
        const auto start = std::chrono::steady_clock::now();
        std::vector<ObjectVisibility> visibility;
        const ImageRGB result = insertObjects(volume, photo, camera, objects, options, &visibility);
        warnOfHiddenObjects(o, objects, camera, visibility);
        writeOutput(result, o.output, o);
        std::cerr << objects.size() << " object(s) inserted in "
                  << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
                  << " s -> " << o.output << "\n";
        return;
    }
    // Along a path: the first object moves; frames, a contact sheet, and the epipolar image
    // (the middle row of an envmap at each position, stacked top to bottom).
    const std::vector<Vec3d> path = readPointsFile(o.path);
    std::vector<std::vector<ImageRGB>> sheet(1);
    ImageRGB epipolar(240, int(path.size()));
    const InsertedObject first = objects[0];
    for (std::size_t i = 0; i < path.size(); ++i) {
        TriangleMesh mesh = first.mesh;
        mesh.transform(1.0, Mat3d::identity(), path[i] - first.centre);
        objects[0] = InsertedObject{mesh, first.material, path[i], first.radius};
        const ImageRGB frame = insertObjects(volume, photo, camera, objects, options);
        writeOutput(frame, numberedPath(o.output, int(i)), o);
        if (sheet.back().size() == 4) sheet.emplace_back();
        sheet.back().push_back(frame);
        const ImageRGB env = renderEnvmap(volume, path[i], {240, 120, options.march});
        std::copy(env.at(0, 60), env.at(0, 60) + 240 * 3, epipolar.at(0, int(i)));
        std::cerr << "[" << i + 1 << "/" << path.size() << "] object at (" << path[i].x() << ", "
                  << path[i].y() << ", " << path[i].z() << ") -> " << numberedPath(o.output, int(i))
                  << "\n";
    }
    writePng(contactSheet(sheet, 120), withExtension(o.output, "") + "_sheet.png", o.exposure);
    writePng(resizeImage(epipolar, 480, std::max(2, int(path.size()) * 4)),
             withExtension(o.output, "") + "_epipolar.png", o.exposure);
    std::cerr << "contact sheet and epipolar image written beside " << o.output << "\n";
}

}  // namespace

void addInsertCommand(CLI::App& app) {
    auto o = std::make_shared<InsertCommandOptions>();
    CLI::App* cmd = app.add_subcommand("insert",
                                       "Insert virtual objects into a photograph, lit at every "
                                       "surface point by a lighting volume");
    cmd->add_option("volume", o->volume, "Lighting volume (.vdb)")->required();
    cmd->add_option("--image", o->image, "The photograph (PNG/JPEG sRGB or linear EXR)")
        ->required();
    cmd->add_option("--cameras", o->cameras, "cameras.json of the photograph")->required();
    cmd->add_option("--view", o->view, "Camera of the photograph: ref, src or tgt")
        ->capture_default_str();
    // Each repeatable option takes one value per use, so that a plain argument after it is
    // the volume, not a second value.
    cmd->add_option("--object", o->objects,
                    "sphere, cube, torus, cylinder or an .obj file (repeat per object)")
        ->required()
        ->allow_extra_args(false);
    cmd->add_option("--at", o->at, "Object centre X,Y,Z in the world frame (one per object)")
        ->required()
        ->allow_extra_args(false);
    cmd->add_option("--scale", o->scales,
                    "Object radius, scene units (default 0.2; once for all or per object)")
        ->allow_extra_args(false);
    cmd->add_option("--rotate", o->rotations,
                    "Euler angles RX,RY,RZ in degrees (once for all or per object)")
        ->allow_extra_args(false);
    cmd->add_option(
           "--material", o->materials,
           "mirror | glossy:ROUGHNESS | diffuse:R,G,B (default mirror; once for all or per object)")
        ->allow_extra_args(false);
    cmd->add_option("--samples", o->insert.samples, "Rays per glossy/diffuse shading point")
        ->capture_default_str();
    cmd->add_option("--pixel-samples", o->insert.pixelSamples, "Primary rays per pixel and axis")
        ->capture_default_str();
    cmd->add_option("--max-depth", o->insert.maxDepth, "Object-to-object bounces")
        ->capture_default_str();
    cmd->add_option("--shadow-rays", o->insert.shadowRays, "Rays per background pixel for shadows")
        ->capture_default_str();
    cmd->add_flag("--no-shadows", o->noShadows, "Do not darken the scene around objects");
    cmd->add_flag(
        "--single-envmap", o->insert.singleEnvmap,
        "Light each object by one envmap at its centre (to compare with per-point lighting)");
    cmd->add_option("--path", o->path,
                    "Move the first object along the points of this file: frames, contact sheet, "
                    "epipolar image");
    addImageFlags(cmd, o->alsoPng, o->exposure);
    addStrictFlag(cmd, o->strict);
    cmd->add_option("-o,--output", o->output, "Output .png (sRGB) or .exr (linear)")->required();
    cmd->callback([o] { runInsert(*o); });
}

}  // namespace lh::cli
