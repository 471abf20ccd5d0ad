// `lighthouse edit IN.vdb [--crop ...] [--erase-box ...] [--add-box ...] [--add-sphere ...]
//  [--scale-density K] [--scale-radiance K] [--clamp-density D] [--clamp-radiance R] -o OUT.vdb`
#include "cli/cli_common.h"
#include "cli/commands.h"
#include "cli/common_options.h"
#include "core/atomic_file.h"
#include "core/errors.h"
#include "core/path_guard.h"
#include "vdb/volume_edit.h"
#include "vdb/volume_io.h"

#include <cstdio>
#include <iostream>
#include <optional>
#include <sstream>

namespace lh::cli {

namespace {

struct EditOptions {
    std::string input, output, crop;
    std::vector<std::string> eraseBoxes, addBoxes, addSpheres;
    float scaleDensity = 1, scaleRadiance = 1;
    std::optional<float> clampDensity, clampRadiance;  // not given: no clamp
    bool half = false;
    bool strict = false;
};

constexpr float kDefaultSigma = 100.f;  // per scene unit: opaque over a few centimetres

std::vector<double> numbers(const std::string& text, std::size_t count, const std::string& what) {
    std::string s = text;
    for (char& c : s)
        if (c == ',') c = ' ';
    std::istringstream in(s);
    std::vector<double> v(count);
    std::string rest;
    for (double& x : v)
        if (!(in >> x))
            throw InputError(what + ": expected " + std::to_string(count) + " numbers, got '" +
                             text + "'");
    if (in >> rest)
        throw InputError(what + ": expected " + std::to_string(count) + " numbers, got '" + text +
                         "'");
    return v;
}

WorldBox parseBox(const std::string& text, const std::string& what) {
    const auto v = numbers(text, 6, what + " (X0,Y0,Z0,X1,Y1,Z1)");
    return {Vec3d(v[0], v[1], v[2]), Vec3d(v[3], v[4], v[5])};
}

// An edit that changed no voxel (its shape misses every voxel centre) is an error, not
// "applied": `changed` is what the edit function returned.
void requireChanged(std::size_t changed, const LightingVolume& volume, const std::string& what,
                    const std::string& text) {
    if (changed > 0) return;
    const WorldBox outer = volume.levels.front().worldBounds();
    char bounds[160];
    std::snprintf(bounds, sizeof bounds, "[%g, %g] x [%g, %g] x [%g, %g]", outer.min.x(),
                  outer.max.x(), outer.min.y(), outer.max.y(), outer.min.z(), outer.max.z());
    throw InputError(what + " " + text +
                     " lies wholly outside the volume (its coarsest level covers " + bounds +
                     ") or between its voxel centres, so it would change nothing");
}

// "GEOMETRY:R,G,B[:SIGMA]" -> the three parts.
void splitEmitter(const std::string& text, const std::string& what, std::string& geometry,
                  openvdb::Vec3s& radiance, float& sigma) {
    const auto a = text.find(':');
    if (a == std::string::npos)
        throw InputError(what + ": expected GEOMETRY:R,G,B[:SIGMA], got '" + text + "'");
    const auto b = text.find(':', a + 1);
    geometry = text.substr(0, a);
    const auto rgb =
        numbers(text.substr(a + 1, b == std::string::npos ? std::string::npos : b - a - 1), 3,
                what + " radiance");
    radiance = openvdb::Vec3s(float(rgb[0]), float(rgb[1]), float(rgb[2]));
    sigma = b == std::string::npos ? kDefaultSigma
                                   : float(numbers(text.substr(b + 1), 1, what + " density")[0]);
}

void runEdit(const EditOptions& o) {
    requireVdbOutput(o.output, "the edited lighting volume");
    if (o.clampDensity && !(*o.clampDensity > 0))
        throw InputError("--clamp-density must be a positive density per scene unit, got " +
                         std::to_string(*o.clampDensity));
    if (o.clampRadiance && !(*o.clampRadiance > 0))
        throw InputError("--clamp-radiance must be a positive radiance, got " +
                         std::to_string(*o.clampRadiance));
    requireOutputIsNotAnInput(o.output, "-o", {{o.input, "the input volume"}});
    LightingVolume volume = loadVolumeForCli(o.input, o.strict);
    int edits = 0;
    if (!o.crop.empty())
        cropToBox(volume, parseBox(o.crop, "--crop")), ++edits;  // refuses a box outside the volume
    for (const auto& e : o.eraseBoxes) {
        requireChanged(eraseBox(volume, parseBox(e, "--erase-box")), volume, "--erase-box", e);
        ++edits;
    }
    for (const auto& e : o.addBoxes) {
        std::string geometry;
        openvdb::Vec3s radiance;
        float sigma;
        splitEmitter(e, "--add-box", geometry, radiance, sigma);
        requireChanged(addEmissiveBox(volume, parseBox(geometry, "--add-box"), radiance, sigma),
                       volume, "--add-box", geometry);
        ++edits;
    }
    for (const auto& e : o.addSpheres) {
        std::string geometry;
        openvdb::Vec3s radiance;
        float sigma;
        splitEmitter(e, "--add-sphere", geometry, radiance, sigma);
        const auto v = numbers(geometry, 4, "--add-sphere (X,Y,Z,RADIUS)");
        requireChanged(addEmissiveSphere(volume, Vec3d(v[0], v[1], v[2]), v[3], radiance, sigma),
                       volume, "--add-sphere", geometry);
        ++edits;
    }
    if (o.scaleDensity != 1.f) scaleDensity(volume, o.scaleDensity), ++edits;
    if (o.scaleRadiance != 1.f) scaleExposure(volume, o.scaleRadiance), ++edits;
    if (o.clampDensity || o.clampRadiance) {
        clampValues(volume, o.clampDensity.value_or(std::numeric_limits<float>::max()),
                    o.clampRadiance.value_or(std::numeric_limits<float>::max()));
        ++edits;
    }
    if (edits == 0) throw InputError("no edit given: see 'lighthouse edit --help'");
    warnOfHalfClamping(saveVolume(o.output, volume, VolumeSaveOptions{o.half}), "--half");
    std::cerr << edits << " edit(s) applied -> " << o.output << "\n";
}

}  // namespace

void addEditCommand(CLI::App& app) {
    auto o = std::make_shared<EditOptions>();
    CLI::App* cmd = app.add_subcommand("edit",
                                       "Edit a lighting volume: add emissive boxes/spheres, erase, "
                                       "crop, scale, clamp (applied in that order: "
                                       "crop, erase, add, density, radiance, clamp)");
    cmd->add_option("input", o->input, "Lighting volume (.vdb)")->required();
    cmd->add_option("-o,--output", o->output, "Edited volume (.vdb)")->required();
    cmd->add_option("--crop", o->crop, "Keep only X0,Y0,Z0,X1,Y1,Z1 (world frame)");
    cmd->add_option("--erase-box", o->eraseBoxes, "Empty X0,Y0,Z0,X1,Y1,Z1 (repeatable)")
        ->allow_extra_args(false);
    cmd->add_option("--add-box", o->addBoxes,
                    "Emissive box X0,Y0,Z0,X1,Y1,Z1:R,G,B[:SIGMA] (repeatable; SIGMA default 100)")
        ->allow_extra_args(false);
    cmd->add_option("--add-sphere", o->addSpheres,
                    "Emissive sphere X,Y,Z,RADIUS:R,G,B[:SIGMA] (repeatable)")
        ->allow_extra_args(false);
    cmd->add_option("--scale-density", o->scaleDensity, "Multiply every density by K");
    cmd->add_option("--scale-radiance", o->scaleRadiance, "Multiply every radiance by K");
    cmd->add_option("--clamp-density", o->clampDensity,
                    "Clamp densities to at most D (> 0, per scene unit)");
    cmd->add_option("--clamp-radiance", o->clampRadiance,
                    "Clamp radiance components to at most R (> 0)");
    addHalfFlag(cmd, o->half);
    addStrictFlag(cmd, o->strict);
    cmd->callback([o] { runEdit(*o); });
}

}  // namespace lh::cli
