#include "cameras/exif_camera.h"

#include "cameras/colmap_convert.h"
#include "core/errors.h"

#include <libexif/exif-data.h>
#include <stb/stb_image.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <sstream>

namespace lh {

namespace {

constexpr double kFullFrameDiagonalMm = 43.266615305567875;  // sqrt(36^2 + 24^2)

struct ExifDataDeleter {
    void operator()(ExifData* d) const { exif_data_unref(d); }
};

// The first component of a numeric entry (SHORT, LONG, RATIONAL, SRATIONAL); empty for any
// other format, a zero denominator or a truncated entry.
std::optional<double> entryValue(ExifData* data, ExifIfd ifd, ExifTag tag) {
    ExifEntry* e = exif_content_get_entry(data->ifd[ifd], tag);
    if (!e || !e->data || e->components < 1) return std::nullopt;
    const ExifByteOrder order = exif_data_get_byte_order(data);
    if (e->size < exif_format_get_size(e->format)) return std::nullopt;
    switch (e->format) {
        case EXIF_FORMAT_SHORT:
            return double(exif_get_short(e->data, order));
        case EXIF_FORMAT_LONG:
            return double(exif_get_long(e->data, order));
        case EXIF_FORMAT_RATIONAL: {
            const ExifRational r = exif_get_rational(e->data, order);
            if (r.denominator == 0) return std::nullopt;
            return double(r.numerator) / double(r.denominator);
        }
        case EXIF_FORMAT_SRATIONAL: {
            const ExifSRational r = exif_get_srational(e->data, order);
            if (r.denominator == 0) return std::nullopt;
            return double(r.numerator) / double(r.denominator);
        }
        default:
            return std::nullopt;
    }
}

std::string number(double v) {
    std::ostringstream ss;
    ss.precision(6);
    ss << v;
    return ss.str();
}

}  // namespace

ExifCameraInfo readExifCameraInfo(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw FileError("photo '" + path + "' does not exist");
    if (!std::filesystem::is_regular_file(path, ec))
        throw FileError("photo '" + path + "' is not a regular file");
    ExifCameraInfo info;
    int channels = 0;
    if (!stbi_info(path.c_str(), &info.storedWidth, &info.storedHeight, &channels)) {
        const char* why = stbi_failure_reason();
        throw FileError("cannot read photo '" + path + "': " + (why ? why : "unknown format") +
                        " (JPEG or PNG expected)");
    }
    std::unique_ptr<ExifData, ExifDataDeleter> data(exif_data_new_from_file(path.c_str()));
    if (!data) return info;  // no EXIF (a PNG, or a JPEG without APP1)
    ExifData* d = data.get();
    if (auto o = entryValue(d, EXIF_IFD_0, EXIF_TAG_ORIENTATION); o && *o >= 1 && *o <= 8)
        info.orientation = int(*o);
    if (auto f = entryValue(d, EXIF_IFD_EXIF, EXIF_TAG_FOCAL_LENGTH_IN_35MM_FILM); f && *f > 0)
        info.focal35mm = *f;  // 0 means "unknown" in the EXIF standard
    if (auto f = entryValue(d, EXIF_IFD_EXIF, EXIF_TAG_FOCAL_LENGTH); f && *f > 0)
        info.focalMm = *f;
    const auto res = entryValue(d, EXIF_IFD_EXIF, EXIF_TAG_FOCAL_PLANE_X_RESOLUTION);
    // FocalPlaneResolutionUnit: 2 inch (the default), 3 cm; 4 mm and 5 um are TIFF/EP's.
    const auto unit = entryValue(d, EXIF_IFD_EXIF, EXIF_TAG_FOCAL_PLANE_RESOLUTION_UNIT);
    double unitMm = 25.4;
    if (unit) {
        const int u = int(*unit);
        unitMm = u == 3 ? 10.0 : u == 4 ? 1.0 : u == 5 ? 1e-3 : u == 2 ? 25.4 : 0.0;
    }
    if (res && *res > 0 && unitMm > 0) info.planePixelsPerMm = *res / unitMm;
    if (auto w = entryValue(d, EXIF_IFD_EXIF, EXIF_TAG_PIXEL_X_DIMENSION); w && *w >= 1)
        info.pixelXDimension = int(*w);
    return info;
}

double exifFocalPixels(const ExifCameraInfo& info, const std::string& path, std::string* source) {
    const double w = info.width(), h = info.height();
    if (info.focal35mm) {
        if (source) *source = "FocalLengthIn35mmFilm " + number(*info.focal35mm) + " mm";
        return *info.focal35mm * std::sqrt(w * w + h * h) / kFullFrameDiagonalMm;
    }
    if (info.focalMm && info.planePixelsPerMm) {
        // The focal-plane resolution counts pixels of the stored image as captured; a photo
        // resized afterwards keeps its tags but not its pixel count.
        double fx = *info.focalMm * *info.planePixelsPerMm;
        if (info.pixelXDimension) fx *= double(info.storedWidth) / *info.pixelXDimension;
        if (source)
            *source = "FocalLength " + number(*info.focalMm) + " mm and FocalPlaneXResolution";
        return fx;
    }
    throw InputError("photo '" + path +
                     "' has no usable EXIF focal length "
                     "(FocalLengthIn35mmFilm, or FocalLength with FocalPlaneXResolution); "
                     "give --fx in pixels, or use --photos or --colmap");
}

CamerasFile exifStereoPair(const std::string& refPath, const std::string& srcPath,
                           const ExifPairOptions& o, std::string* report) {
    checkBaseline(o.baseline);
    if (o.fx && !(std::isfinite(*o.fx) && *o.fx > 0))
        throw InputError("--fx must be a positive finite focal length in pixels (got " +
                         number(*o.fx) + ")");
    const ExifCameraInfo ri = readExifCameraInfo(refPath), si = readExifCameraInfo(srcPath);
    if (ri.width() != si.width() || ri.height() != si.height())
        throw InputError("a rectified pair needs two photos of one size: '" + refPath + "' is " +
                         std::to_string(ri.width()) + "x" + std::to_string(ri.height()) + " and '" +
                         srcPath + "' is " + std::to_string(si.width()) + "x" +
                         std::to_string(si.height()) + " (orientation applied)");
    std::ostringstream log;
    auto camera = [&](const ExifCameraInfo& info, const std::string& path) {
        PinholeCamera c;
        c.width = info.width();
        c.height = info.height();
        std::string source = "--fx";
        c.fx = c.fy = o.fx ? *o.fx : exifFocalPixels(info, path, &source);
        c.cx = 0.5 * c.width;  // pixel centres at +0.5: the image centre is at W/2, H/2
        c.cy = 0.5 * c.height;
        log << path << ": " << c.width << "x" << c.height << ", fx " << number(c.fx) << " px from "
            << source;
        if (info.orientation != 1) log << ", EXIF orientation " << info.orientation;
        log << "\n";
        c.validate("photo '" + path + "'");
        return c;
    };
    CamerasFile cams;
    cams.ref = camera(ri, refPath);
    PinholeCamera src = camera(si, srcPath);
    src.position = Vec3d(o.baseline, 0.0, 0.0);
    cams.src = src;
    cams.near = o.near;
    cams.far = o.far;
    if (cams.near && !(std::isfinite(*cams.near) && *cams.near > 0))
        throw InputError("--near must be a positive finite depth (got " + number(*cams.near) + ")");
    if (cams.far && !(std::isfinite(*cams.far) && *cams.far > 0))
        throw InputError("--far must be a positive finite depth (got " + number(*cams.far) + ")");
    if (cams.near && cams.far && !(*cams.near < *cams.far))
        throw InputError("--near " + number(*cams.near) + " must be smaller than --far " +
                         number(*cams.far));
    if (report) *report = log.str();
    return cams;
}

}  // namespace lh
