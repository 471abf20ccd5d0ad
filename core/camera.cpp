#include "core/camera.h"

#include "core/errors.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <sstream>

namespace lh {

using nlohmann::json;

Vec3d PinholeCamera::pixelDirection(double px, double py) const {
    Vec3d cam((px - cx) / fx, (py - cy) / fy, 1.0);
    Vec3d d = rotation * cam;
    return d.unitSafe();
}

Vec3d PinholeCamera::worldToCamera(const Vec3d& world) const {
    // rotation is orthonormal, so its inverse is its transpose.
    return rotation.transpose() * (world - position);
}

Vec3d PinholeCamera::cameraToPixel(const Vec3d& cam) const {
    return Vec3d(fx * cam.x() / cam.z() + cx, fy * cam.y() / cam.z() + cy, cam.z());
}

std::optional<Vec3d> PinholeCamera::projectIntoImage(const Vec3d& world) const {
    const Vec3d cam = worldToCamera(world);
    if (!(cam.z() > kMinImageDepth)) return std::nullopt;
    const Vec3d pixel = cameraToPixel(cam);
    if (!(pixel.x() >= 0 && pixel.y() >= 0 && pixel.x() < width && pixel.y() < height))
        return std::nullopt;
    return pixel;
}

PinholeCamera PinholeCamera::resized(int newWidth, int newHeight) const {
    PinholeCamera c = *this;
    const double sx = double(newWidth) / width, sy = double(newHeight) / height;
    c.width = newWidth;
    c.height = newHeight;
    c.fx *= sx;
    c.cx *= sx;
    c.fy *= sy;
    c.cy *= sy;
    return c;
}

void PinholeCamera::validate(const std::string& what) const {
    auto fail = [&](const std::string& why) { throw InputError(what + ": " + why); };
    if (width <= 0 || height <= 0) fail("image size must be positive");
    if (width > 65536 || height > 65536) fail("image size over 65536 pixels per side");
    for (double v : {fx, fy, cx, cy})
        if (!std::isfinite(v)) fail("intrinsics must be finite");
    if (fx <= 0 || fy <= 0) fail("focal lengths fx, fy must be positive");
    for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(position[i])) fail("camera position must be finite");
        for (int j = 0; j < 3; ++j)
            if (!std::isfinite(rotation(i, j))) fail("rotation must be finite");
    }
    Mat3d should = rotation.transpose() * rotation;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (std::abs(should(i, j) - (i == j ? 1.0 : 0.0)) > 1e-4)
                fail("cam_to_world rotation is not orthonormal");
    if (std::abs(rotation.det() - 1.0) > 1e-4)
        fail("cam_to_world rotation has determinant " + std::to_string(rotation.det()) +
             " (a reflection); expected +1");
}

namespace {

json cameraJson(const PinholeCamera& c) {
    json m = json::array();
    for (int i = 0; i < 3; ++i)
        m.push_back({c.rotation(i, 0), c.rotation(i, 1), c.rotation(i, 2), c.position[i]});
    m.push_back({0.0, 0.0, 0.0, 1.0});
    return {{"width", c.width}, {"height", c.height}, {"fx", c.fx},       {"fy", c.fy},
            {"cx", c.cx},       {"cy", c.cy},         {"cam_to_world", m}};
}

double number(const json& j, const char* key, const std::string& where) {
    if (!j.contains(key)) throw InputError(where + ": missing key '" + key + "'");
    if (!j[key].is_number()) throw InputError(where + ": '" + key + "' must be a number");
    return j[key].get<double>();
}

PinholeCamera parseCamera(const json& j, const std::string& where) {
    if (!j.is_object()) throw InputError(where + ": must be an object");
    PinholeCamera c;
    double w = number(j, "width", where), h = number(j, "height", where);
    if (w != std::floor(w) || h != std::floor(h) || w < 1 || h < 1 || w > 65536 || h > 65536)
        throw InputError(where + ": width and height must be whole numbers in [1, 65536]");
    c.width = int(w);
    c.height = int(h);
    c.fx = number(j, "fx", where);
    c.fy = number(j, "fy", where);
    c.cx = number(j, "cx", where);
    c.cy = number(j, "cy", where);
    if (j.contains("cam_to_world")) {
        const json& m = j["cam_to_world"];
        bool shapeOk = m.is_array() && m.size() == 4;
        for (std::size_t r = 0; shapeOk && r < 4; ++r) {
            shapeOk = m[r].is_array() && m[r].size() == 4;
            for (std::size_t k = 0; shapeOk && k < 4; ++k) shapeOk = m[r][k].is_number();
        }
        if (!shapeOk) throw InputError(where + ": cam_to_world must be a 4x4 array of numbers");
        for (int r = 0; r < 3; ++r) {
            for (int k = 0; k < 3; ++k) c.rotation(r, k) = m[r][k].get<double>();
            c.position[r] = m[r][3].get<double>();
        }
        const double bottom[4] = {0, 0, 0, 1};
        for (int k = 0; k < 4; ++k)
            if (std::abs(m[3][k].get<double>() - bottom[k]) > 1e-9)
                throw InputError(where + ": cam_to_world last row must be [0, 0, 0, 1]");
    }
    c.validate(where);
    return c;
}

Vec3d parseVec3(const json& j, const std::string& where) {
    if (!j.is_array() || j.size() != 3 || !j[0].is_number() || !j[1].is_number() ||
        !j[2].is_number())
        throw InputError(where + ": must be an array of 3 numbers");
    Vec3d v(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(v[i])) throw InputError(where + ": must be finite");
    return v;
}

// The string at `key`, "" when absent; a value of another type is refused (json's get would
// throw its own type_error, which callers do not expect).
std::string optionalString(const json& j, const char* key, const std::string& where) {
    if (!j.contains(key)) return "";
    if (!j[key].is_string()) throw InputError(where + ": '" + key + "' must be a string");
    return j[key].get<std::string>();
}

}  // namespace

const PinholeCamera& CamerasFile::view(const std::string& name) const {
    if (name == "ref") return ref;
    if (name == "src" && src) return *src;
    if (name == "tgt" && tgt) return *tgt;
    throw InputError("cameras file has no view '" + name + "' (expected ref, src or tgt)");
}

CamerasFile parseCamerasJson(const std::string& text, const std::string& sourceName) {
    json j;
    try {
        j = json::parse(text);
    } catch (const json::exception& e) {
        throw FileError(sourceName + ": not valid JSON (" + std::string(e.what()) + ")");
    }
    if (!j.is_object()) throw InputError(sourceName + ": top level must be a JSON object");
    if (!j.contains("ref")) throw InputError(sourceName + ": missing camera 'ref'");
    CamerasFile cams;
    cams.ref = parseCamera(j["ref"], sourceName + ": ref");
    if (j.contains("src")) cams.src = parseCamera(j["src"], sourceName + ": src");
    if (j.contains("tgt")) cams.tgt = parseCamera(j["tgt"], sourceName + ": tgt");
    if (j.contains("near")) cams.near = number(j, "near", sourceName);
    if (j.contains("far")) cams.far = number(j, "far", sourceName);
    if (cams.near && !(std::isfinite(*cams.near) && *cams.near > 0))
        throw InputError(sourceName + ": near must be a positive finite depth");
    if (cams.far && !(std::isfinite(*cams.far) && *cams.far > 0))
        throw InputError(sourceName + ": far must be a positive finite depth");
    if (cams.near && cams.far && !(*cams.near < *cams.far))
        throw InputError(sourceName + ": near (" + std::to_string(*cams.near) +
                         ") must be smaller than far (" + std::to_string(*cams.far) + ")");
    if (j.contains("envmaps")) {
        if (!j["envmaps"].is_array()) throw InputError(sourceName + ": envmaps must be an array");
        for (const json& e : j["envmaps"]) {
            std::string where = sourceName + ": envmaps";
            if (!e.is_object() || !e.contains("position"))
                throw InputError(where + ": each entry needs a 'position'");
            EnvmapSample s;
            s.position = parseVec3(e["position"], where + ".position");
            s.file = optionalString(e, "file", where);
            s.positionFile = optionalString(e, "position_file", where);
            cams.envmaps.push_back(s);
        }
    }
    return cams;
}

CamerasFile loadCamerasFile(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw FileError("cannot open cameras file '" + path + "'");
    std::stringstream ss;
    ss << in.rdbuf();
    return parseCamerasJson(ss.str(), path);
}

std::string camerasToJson(const CamerasFile& cams) {
    json j;
    j["ref"] = cameraJson(cams.ref);
    if (cams.src) j["src"] = cameraJson(*cams.src);
    if (cams.tgt) j["tgt"] = cameraJson(*cams.tgt);
    if (cams.near) j["near"] = *cams.near;
    if (cams.far) j["far"] = *cams.far;
    if (!cams.envmaps.empty()) {
        j["envmaps"] = json::array();
        for (const auto& e : cams.envmaps) {
            json o = {{"position", {e.position[0], e.position[1], e.position[2]}}};
            if (!e.file.empty()) o["file"] = e.file;
            if (!e.positionFile.empty()) o["position_file"] = e.positionFile;
            j["envmaps"].push_back(o);
        }
    }
    return j.dump(2);
}

std::string cameraToJson(const PinholeCamera& camera) { return cameraJson(camera).dump(); }

PinholeCamera cameraFromJson(const std::string& text, const std::string& sourceName) {
    try {
        return parseCamera(json::parse(text), sourceName);
    } catch (const json::exception& e) {
        throw FileError(sourceName + ": camera metadata is not valid JSON");
    }
}

}  // namespace lh
