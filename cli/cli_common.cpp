#include "cli/cli_common.h"

#include "core/atomic_file.h"
#include "core/errors.h"
#include "vdb/volume_io.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>

namespace lh::cli {

Vec3d parsePoint(const std::string& text, const std::string& what) {
    std::string s = text;
    for (char& c : s)
        if (c == ',') c = ' ';
    // strtod, unlike istream, parses "nan" and "inf", so they get the finiteness message.
    double v[3];
    const char* p = s.c_str();
    for (double& x : v) {
        char* end = nullptr;
        x = std::strtod(p, &end);
        if (end == p) throw InputError(what + ": expected three numbers X,Y,Z, got '" + text + "'");
        p = end;
    }
    if (std::string(p).find_first_not_of(" \t\r") != std::string::npos)
        throw InputError(what + ": expected three numbers X,Y,Z, got '" + text + "'");
    for (double x : v)
        if (!std::isfinite(x))
            throw InputError(what + ": coordinates must be finite, got '" + text + "'");
    return Vec3d(v[0], v[1], v[2]);
}

std::vector<Vec3d> readPointsFile(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw FileError("cannot open points file '" + path + "'");
    std::vector<Vec3d> points;
    std::string line;
    int number = 0;
    while (std::getline(in, line)) {
        ++number;
        line = line.substr(0, line.find('#'));
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        points.push_back(parsePoint(line, path + ":" + std::to_string(number)));
    }
    if (points.empty()) throw InputError("points file '" + path + "' holds no points");
    return points;
}

void parseSize(const std::string& text, int& width, int& height) {
    const auto x = text.find_first_of("xX");
    try {
        if (x == std::string::npos) throw std::invalid_argument("no x");
        std::size_t used = 0;
        width = std::stoi(text.substr(0, x), &used);
        if (used != x) throw std::invalid_argument("width");
        const std::string h = text.substr(x + 1);
        height = std::stoi(h, &used);
        if (used != h.size()) throw std::invalid_argument("height");
    } catch (const std::logic_error&) {
        throw InputError("size must be WxH, for example 240x120, got '" + text + "'");
    }
}

LightingVolume loadVolumeForCli(const std::string& path, bool strict) {
    std::vector<std::string> warnings;
    VolumeLoadOptions options;
    options.nonFinite = strict ? NonFinitePolicy::Reject : NonFinitePolicy::Sanitise;
    LightingVolume volume = loadVolume(path, &warnings, options);
    for (const auto& w : warnings) std::cerr << "warning: " << w << "\n";
    return volume;
}

VolumeFile loadVolumeFileForCli(const std::string& path, bool strict) {
    std::vector<std::string> warnings;
    VolumeLoadOptions options;
    options.nonFinite = strict ? NonFinitePolicy::Reject : NonFinitePolicy::Sanitise;
    VolumeFile file = loadVolumeFile(path, &warnings, options);
    for (const auto& w : warnings) std::cerr << "warning: " << w << "\n";
    return file;
}

std::string numberedPath(const std::string& path, int index) {
    std::filesystem::path p(path);
    char suffix[16];
    std::snprintf(suffix, sizeof suffix, "_%03d", index);
    return (p.parent_path() / (p.stem().string() + suffix + p.extension().string())).string();
}

std::string withExtension(const std::string& path, const std::string& extension) {
    return std::filesystem::path(path).replace_extension(extension).string();
}

void requireVdbOutput(const std::string& path, const std::string& what) {
    if (fileExtension(path) != ".vdb")
        throw InputError("output '" + path + "' must end in .vdb (" + what + ")");
}

void warnOfHalfClamping(const VolumeSaveReport& saved, const std::string& hint) {
    const std::string warning = halfClampWarning(saved);
    if (!warning.empty()) std::cerr << "warning: " << warning << " (" << hint << ")\n";
}

void warnOfPointsOutside(const LightingVolume& volume, const std::vector<Vec3d>& points) {
    for (const Vec3d& p : points) {
        if (finestLevelAt(volume, p) < 0)
            std::cerr << "warning: point (" << p.x() << ", " << p.y() << ", " << p.z()
                      << ") lies outside every level of the volume: its envmap sees the volume "
                         "from outside\n";
    }
}

}  // namespace lh::cli
