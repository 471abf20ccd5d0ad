#include "synth/scene_json.h"

#include "core/errors.h"

#include <nlohmann/json.hpp>

#include <fstream>
#include <sstream>

namespace lh::synth {

using nlohmann::json;

namespace {

json vec(const Vec3d& v) { return {v.x(), v.y(), v.z()}; }
Vec3d vec(const json& j) {
    return Vec3d(j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>());
}

json mat(const Mat3d& m) {
    return {{m(0, 0), m(0, 1), m(0, 2)}, {m(1, 0), m(1, 1), m(1, 2)}, {m(2, 0), m(2, 1), m(2, 2)}};
}
Mat3d mat(const json& j) {
    Mat3d m;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) m(r, c) = j.at(r).at(c).get<double>();
    return m;
}

const char* kTextureNames[] = {"plain", "checker", "stripes", "noise",
                               "wood",  "brick",   "bands",   "rings"};
const char* kMaterialNames[] = {"diffuse", "glossy", "metal"};
const char* kShapeNames[] = {"box", "sphere", "cylinder", "quad"};
const char* kEmissionNames[] = {"none", "constant", "window"};

template <std::size_t N>
int indexOf(const char* const (&names)[N], const std::string& name) {
    for (std::size_t i = 0; i < N; ++i)
        if (name == names[i]) return int(i);
    throw std::invalid_argument("unknown name '" + name + "'");
}

json textureJson(const Texture& t) {
    return {{"kind", kTextureNames[int(t.kind)]},
            {"color_a", vec(t.colorA)},
            {"color_b", vec(t.colorB)},
            {"scale", t.scale},
            {"noise_seed", t.noiseSeed}};
}

Texture textureFrom(const json& j) {
    Texture t;
    t.kind = TextureKind(indexOf(kTextureNames, j.at("kind").get<std::string>()));
    t.colorA = vec(j.at("color_a"));
    t.colorB = vec(j.at("color_b"));
    t.scale = j.at("scale").get<double>();
    t.noiseSeed = j.at("noise_seed").get<uint32_t>();
    return t;
}

json materialJson(const Material& m) {
    return {{"kind", kMaterialNames[int(m.kind)]}, {"f0", vec(m.f0)}, {"roughness", m.roughness}};
}

Material materialFrom(const json& j) {
    Material m;
    m.kind = MaterialKind(indexOf(kMaterialNames, j.at("kind").get<std::string>()));
    m.f0 = vec(j.at("f0"));
    m.roughness = j.at("roughness").get<double>();
    return m;
}

}  // namespace

std::string sceneToJson(const Scene& scene, const BakeOptions& bake) {
    json prims = json::array();
    for (const Primitive& p : scene.primitives) {
        json o = {{"shape", kShapeNames[int(p.shape)]},
                  {"label", p.label},
                  {"centre", vec(p.centre)},
                  {"rotation", mat(p.rotation)},
                  {"half", vec(p.half)},
                  {"inverted", p.inverted},
                  {"texture", textureJson(p.texture)},
                  {"material", materialJson(p.material)},
                  {"emission", kEmissionNames[int(p.emission)]},
                  {"radiance", vec(p.radiance)},
                  {"window", p.window}};
        if (!p.faceTextures.empty()) {
            o["face_textures"] = json::array();
            for (const Texture& t : p.faceTextures) o["face_textures"].push_back(textureJson(t));
        }
        prims.push_back(o);
    }
    json windows = json::array();
    for (const WindowView& w : scene.windows)
        windows.push_back({{"panorama", w.panorama},
                           {"yaw", w.yaw},
                           {"scale", w.scale},
                           {"view_centre", vec(w.viewCentre)},
                           {"room_to_world", mat(w.roomToWorld)}});
    json j = {{"seed", scene.seed},
              {"generator_version", scene.generatorVersion},
              {"exposure", scene.exposure},
              {"room_index", scene.roomIndex},
              {"primitives", prims},
              {"windows", windows},
              {"bake",
               {{"texel_size", bake.texelSize},
                {"max_texels", bake.maxTexels},
                {"gather_rays", bake.gatherRays},
                {"light_samples", bake.lightSamples},
                {"bounces", bake.bounces}}},
              {"frame", "reference camera (OpenCV axes: +x right, +y down, +z forward), metres"}};
    return j.dump(1);
}

Scene sceneFromJson(const std::string& text, const std::string& sourceName, BakeOptions* bake) {
    try {
        const json j = json::parse(text);
        Scene s;
        s.seed = j.at("seed").get<uint64_t>();
        s.generatorVersion = j.at("generator_version").get<int>();
        s.exposure = j.at("exposure").get<double>();
        s.roomIndex = j.at("room_index").get<int>();
        for (const json& o : j.at("primitives")) {
            Primitive p;
            p.shape = Shape(indexOf(kShapeNames, o.at("shape").get<std::string>()));
            p.label = o.at("label").get<std::string>();
            p.centre = vec(o.at("centre"));
            p.rotation = mat(o.at("rotation"));
            p.half = vec(o.at("half"));
            p.inverted = o.at("inverted").get<bool>();
            p.texture = textureFrom(o.at("texture"));
            // Scenes of generator version 1 predate materials: every surface was diffuse.
            if (o.contains("material")) p.material = materialFrom(o["material"]);
            p.emission = Emission(indexOf(kEmissionNames, o.at("emission").get<std::string>()));
            p.radiance = vec(o.at("radiance"));
            p.window = o.at("window").get<int>();
            if (o.contains("face_textures"))
                for (const json& t : o["face_textures"]) p.faceTextures.push_back(textureFrom(t));
            s.primitives.push_back(p);
        }
        for (const json& o : j.at("windows")) {
            WindowView w;
            w.panorama = o.at("panorama").get<std::string>();
            w.yaw = o.at("yaw").get<double>();
            w.scale = o.at("scale").get<double>();
            w.viewCentre = vec(o.at("view_centre"));
            w.roomToWorld = mat(o.at("room_to_world"));
            s.windows.push_back(w);
        }
        if (bake && j.contains("bake")) {
            const json& b = j["bake"];
            bake->texelSize = b.at("texel_size").get<double>();
            bake->maxTexels = b.at("max_texels").get<int>();
            bake->gatherRays = b.at("gather_rays").get<int>();
            bake->lightSamples = b.at("light_samples").get<int>();
            bake->bounces = b.at("bounces").get<int>();
        }
        if (s.roomIndex < 0 || s.roomIndex >= int(s.primitives.size()) ||
            !s.primitives[s.roomIndex].inverted)
            throw std::invalid_argument("room_index does not name the room");
        for (const Primitive& p : s.primitives)
            if (p.emission == Emission::Window &&
                (p.window < 0 || p.window >= int(s.windows.size())))
                throw std::invalid_argument("a window names a missing window view");
        return s;
    } catch (const std::exception& e) {
        throw FileError(sourceName + ": not a valid scene description (" + e.what() + ")");
    }
}

Scene loadScene(const std::string& path, BakeOptions* bake) {
    std::ifstream in(path);
    if (!in) throw FileError("cannot open scene file '" + path + "'");
    std::stringstream ss;
    ss << in.rdbuf();
    return sceneFromJson(ss.str(), path, bake);
}

}  // namespace lh::synth
