#include "cameras/colmap_model.h"

#include "core/errors.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace lh {

namespace {

namespace fs = std::filesystem;

struct ModelKind {
    int id;
    const char* name;
    int params;
};

// COLMAP's camera models (src/colmap/sensor/models.h): id, name, parameter count.
constexpr ModelKind kModels[] = {
    {0, "SIMPLE_PINHOLE", 3},
    {1, "PINHOLE", 4},
    {2, "SIMPLE_RADIAL", 4},
    {3, "RADIAL", 5},
    {4, "OPENCV", 8},
    {5, "OPENCV_FISHEYE", 8},
    {6, "FULL_OPENCV", 12},
    {7, "FOV", 5},
    {8, "SIMPLE_RADIAL_FISHEYE", 4},
    {9, "RADIAL_FISHEYE", 5},
    {10, "THIN_PRISM_FISHEYE", 12},
    {11, "RAD_TAN_THIN_PRISM_FISHEYE", 16},
};

// ---- binary files -------------------------------------------------------------------------

// Reads little-endian values from a whole file held in memory, refusing to read past its end
// so that a truncated or corrupt file fails with a message instead of garbage or a huge
// allocation (every count is checked against the bytes left before anything is reserved).
class BinaryReader {
public:
    explicit BinaryReader(const std::string& path) : path_(path) {
        std::ifstream in(path, std::ios::binary);
        if (!in) throw FileError("cannot open COLMAP file '" + path + "'");
        std::ostringstream ss;
        ss << in.rdbuf();
        bytes_ = ss.str();
    }
    template <class T>
    T read(const char* what) {
        need(sizeof(T), what);
        T value;
        std::memcpy(&value, bytes_.data() + pos_, sizeof(T));  // x86 and ARM are little endian
        pos_ += sizeof(T);
        return value;
    }
    void skip(std::uint64_t n, const char* what) {
        need(n, what);
        pos_ += n;
    }
    // A count of records of at least `recordBytes` each: refused when they cannot fit.
    std::uint64_t count(std::uint64_t recordBytes, const char* what) {
        const auto n = read<std::uint64_t>(what);
        if (recordBytes > 0 && n > remaining() / recordBytes)
            fail(std::string("the number of ") + what + " (" + std::to_string(n) +
                 ") does not fit in the file; it is truncated or corrupt");
        return n;
    }
    std::string cstring(const char* what) {
        const auto end = bytes_.find('\0', pos_);
        if (end == std::string::npos) fail(std::string("unterminated ") + what);
        std::string s = bytes_.substr(pos_, end - pos_);
        pos_ = end + 1;
        return s;
    }
    std::uint64_t remaining() const { return bytes_.size() - pos_; }
    [[noreturn]] void fail(const std::string& why) const {
        throw FileError("COLMAP file '" + path_ + "': " + why);
    }

private:
    void need(std::uint64_t n, const char* what) const {
        if (n > remaining())
            fail(std::string("ends inside ") + what + "; it is truncated or corrupt");
    }
    std::string path_;
    std::string bytes_;
    std::size_t pos_ = 0;
};

void checkFinite(const BinaryReader& r, const double* v, int n, const char* what) {
    for (int i = 0; i < n; ++i)
        if (!std::isfinite(v[i])) r.fail(std::string(what) + " is not finite");
}

void readCamerasBinary(const std::string& path, ColmapModel& model) {
    BinaryReader r(path);
    const auto n = r.count(24, "cameras");
    for (std::uint64_t k = 0; k < n; ++k) {
        ColmapCamera c;
        c.id = r.read<std::uint32_t>("a camera id");
        const int modelId = r.read<std::int32_t>("a camera model id");
        c.model = colmapModelName(modelId);
        const int params = colmapModelParamCount(modelId);
        if (params < 0) r.fail("unknown camera model id " + std::to_string(modelId));
        c.width = r.read<std::uint64_t>("a camera width");
        c.height = r.read<std::uint64_t>("a camera height");
        for (int i = 0; i < params; ++i) c.params.push_back(r.read<double>("camera parameters"));
        checkFinite(r, c.params.data(), params, "a camera parameter");
        model.cameras[c.id] = std::move(c);
    }
}

void readImagesBinary(const std::string& path, ColmapModel& model) {
    BinaryReader r(path);
    const auto n = r.count(4 + 7 * 8 + 4 + 1 + 8, "images");
    for (std::uint64_t k = 0; k < n; ++k) {
        ColmapImage im;
        im.id = r.read<std::uint32_t>("an image id");
        for (double& v : im.q) v = r.read<double>("an image quaternion");
        for (double& v : im.t) v = r.read<double>("an image translation");
        checkFinite(r, im.q, 4, "an image quaternion");
        checkFinite(r, im.t, 3, "an image translation");
        im.cameraId = r.read<std::uint32_t>("an image's camera id");
        im.name = r.cstring("image name");
        const auto points = r.count(24, "2D points of an image");
        for (std::uint64_t p = 0; p < points; ++p) {
            r.skip(16, "2D points of an image");  // x, y in pixels
            const auto id = r.read<std::int64_t>("2D points of an image");
            if (id >= 0) im.observedPoints.push_back(id);
        }
        model.images[im.id] = std::move(im);
    }
}

void readPointsBinary(const std::string& path, ColmapModel& model) {
    BinaryReader r(path);
    const auto n = r.count(8 + 24 + 3 + 8 + 8, "3D points");
    for (std::uint64_t k = 0; k < n; ++k) {
        const auto id = r.read<std::int64_t>("a 3D point id");
        std::array<double, 3> xyz;
        for (double& v : xyz) v = r.read<double>("a 3D point position");
        checkFinite(r, xyz.data(), 3, "a 3D point position");
        r.skip(3 + 8, "a 3D point colour and error");
        const auto track = r.count(8, "track elements of a 3D point");
        r.skip(track * 8, "a 3D point track");
        model.points[id] = xyz;
    }
}

// ---- text files ---------------------------------------------------------------------------

class TextReader {
public:
    explicit TextReader(const std::string& path) : path_(path), in_(path) {
        if (!in_) throw FileError("cannot open COLMAP file '" + path + "'");
    }
    // Next line that is neither empty nor a comment; false at the end of the file.
    bool nextRecord(std::istringstream& fields) {
        std::string line;
        while (std::getline(in_, line)) {
            ++lineNo_;
            const auto first = line.find_first_not_of(" \t\r");
            if (first == std::string::npos || line[first] == '#') continue;
            fields = std::istringstream(line);
            return true;
        }
        return false;
    }
    // The very next line, whatever it holds (the 2D points line of images.txt may be empty).
    bool nextLine(std::istringstream& fields) {
        std::string line;
        if (!std::getline(in_, line)) return false;
        ++lineNo_;
        fields = std::istringstream(line);
        return true;
    }
    [[noreturn]] void fail(const std::string& why) const {
        throw FileError("COLMAP file '" + path_ + "', line " + std::to_string(lineNo_) + ": " +
                        why);
    }

private:
    std::string path_;
    std::ifstream in_;
    int lineNo_ = 0;
};

template <class T>
T field(std::istringstream& in, const TextReader& r, const char* what) {
    T value;
    if (!(in >> value)) r.fail(std::string("cannot read ") + what);
    return value;
}

double finiteField(std::istringstream& in, const TextReader& r, const char* what) {
    // Read as text first: istream refuses "nan" and "inf", which must still be named.
    const std::string text = field<std::string>(in, r, what);
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (end == text.c_str() || *end != '\0') r.fail(std::string("cannot read ") + what);
    if (!std::isfinite(v)) r.fail(std::string(what) + " is not finite");
    return v;
}

void readCamerasText(const std::string& path, ColmapModel& model) {
    TextReader r(path);
    std::istringstream in;
    while (r.nextRecord(in)) {
        ColmapCamera c;
        c.id = field<std::uint32_t>(in, r, "the camera id");
        c.model = field<std::string>(in, r, "the camera model");
        c.width = field<std::uint64_t>(in, r, "the camera width");
        c.height = field<std::uint64_t>(in, r, "the camera height");
        const int params = colmapModelParamCount(c.model);
        if (params < 0) r.fail("unknown camera model '" + c.model + "'");
        for (int i = 0; i < params; ++i)
            c.params.push_back(finiteField(in, r, "a camera parameter"));
        model.cameras[c.id] = std::move(c);
    }
}

void readImagesText(const std::string& path, ColmapModel& model) {
    TextReader r(path);
    std::istringstream in;
    while (r.nextRecord(in)) {
        ColmapImage im;
        im.id = field<std::uint32_t>(in, r, "the image id");
        for (double& v : im.q) v = finiteField(in, r, "the image quaternion");
        for (double& v : im.t) v = finiteField(in, r, "the image translation");
        im.cameraId = field<std::uint32_t>(in, r, "the image's camera id");
        // The name is the rest of the line (COLMAP allows no spaces in it, but be lenient).
        std::string name;
        std::getline(in >> std::ws, name);
        while (!name.empty() && (name.back() == '\r' || name.back() == ' ')) name.pop_back();
        if (name.empty()) r.fail("missing image name");
        im.name = name;
        if (r.nextLine(in)) {
            double x, y;
            std::int64_t id;
            while (in >> x >> y >> id)
                if (id >= 0) im.observedPoints.push_back(id);
            if (!in.eof()) r.fail("cannot read the 2D points (X, Y, POINT3D_ID triples)");
        }
        model.images[im.id] = std::move(im);
    }
}

void readPointsText(const std::string& path, ColmapModel& model) {
    TextReader r(path);
    std::istringstream in;
    while (r.nextRecord(in)) {
        const auto id = field<std::int64_t>(in, r, "the 3D point id");
        std::array<double, 3> xyz;
        for (double& v : xyz) v = finiteField(in, r, "the 3D point position");
        model.points[id] = xyz;  // colour, error and track are not needed
    }
}

// `dir/stem.bin` when it exists, else `dir/stem.txt`, else "".
std::string modelFile(const std::string& dir, const std::string& stem) {
    for (const char* ext : {".bin", ".txt"}) {
        const fs::path p = fs::path(dir) / (stem + ext);
        std::error_code ec;
        if (fs::is_regular_file(p, ec)) return p.string();
    }
    return "";
}

bool isBinary(const std::string& path) {
    return path.size() > 4 && path.substr(path.size() - 4) == ".bin";
}

}  // namespace

int colmapModelParamCount(int modelId) {
    for (const auto& m : kModels)
        if (m.id == modelId) return m.params;
    return -1;
}

int colmapModelParamCount(const std::string& modelName) {
    for (const auto& m : kModels)
        if (modelName == m.name) return m.params;
    return -1;
}

std::string colmapModelName(int modelId) {
    for (const auto& m : kModels)
        if (m.id == modelId) return m.name;
    return "";
}

ColmapModel readColmapModel(const std::string& dir, bool readPoints) {
    std::error_code ec;
    if (!fs::exists(dir, ec)) throw FileError("COLMAP model folder '" + dir + "' does not exist");
    if (!fs::is_directory(dir, ec))
        throw FileError("COLMAP model '" + dir +
                        "' is not a folder (give the folder holding "
                        "cameras.txt/.bin, images.txt/.bin and points3D.txt/.bin)");
    ColmapModel model;
    model.dir = dir;
    const std::string cameras = modelFile(dir, "cameras"), images = modelFile(dir, "images");
    if (cameras.empty() || images.empty()) {
        std::string hint;
        for (const char* sub : {"sparse", "sparse/0"})
            if (!modelFile((fs::path(dir) / sub).string(), "cameras").empty()) {
                hint = "; there is one in '" + (fs::path(dir) / sub).string() + "'";
                break;
            }
        throw FileError(
            "no COLMAP model in '" + dir +
            "': " + (cameras.empty() ? "cameras.txt or cameras.bin" : "images.txt or images.bin") +
            " is missing" + hint);
    }
    isBinary(cameras) ? readCamerasBinary(cameras, model) : readCamerasText(cameras, model);
    isBinary(images) ? readImagesBinary(images, model) : readImagesText(images, model);
    if (readPoints) {
        const std::string points = modelFile(dir, "points3D");
        if (points.empty())
            throw FileError("no points3D.txt or points3D.bin in COLMAP model '" + dir +
                            "' (needed for near/far; or give --near and --far)");
        isBinary(points) ? readPointsBinary(points, model) : readPointsText(points, model);
        model.hasPoints = true;
    }
    return model;
}

}  // namespace lh
