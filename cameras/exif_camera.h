// Cameras of a rectified side-by-side pair from the photos' EXIF focal length (read with
// libexif): square pixels, principal point at the image centre, the source camera `baseline`
// metres to the right of the reference (+x), both looking along +z.
#pragma once

#include "core/camera.h"

#include <optional>
#include <string>

namespace lh {

// What one photo's EXIF says about its camera (absent tags stay empty).
struct ExifCameraInfo {
    int storedWidth = 0, storedHeight = 0;   // pixels as stored in the file
    int orientation = 1;                     // EXIF Orientation 1..8; 5..8 swap the axes
    std::optional<double> focal35mm;         // FocalLengthIn35mmFilm, mm
    std::optional<double> focalMm;           // FocalLength, mm
    std::optional<double> planePixelsPerMm;  // FocalPlaneXResolution / its unit, pixels per mm
    std::optional<int> pixelXDimension;      // PixelXDimension: the width the plane refers to

    // The upright image's size (orientation applied), pixels.
    int width() const { return orientation >= 5 ? storedHeight : storedWidth; }
    int height() const { return orientation >= 5 ? storedWidth : storedHeight; }
};

// Reads the size (image header only) and the EXIF tags above. Throws FileError for a missing
// or unreadable image; a photo without EXIF gives empty fields.
ExifCameraInfo readExifCameraInfo(const std::string& path);

// Focal length in pixels of the upright image, and which tags gave it. The 35 mm equivalent is
// taken first: fx = f35 * diagonal_px / 43.27 mm (the 36 x 24 mm frame's diagonal, the usual
// definition of the equivalent); else FocalLength * FocalPlaneXResolution, scaled by
// width / PixelXDimension when the image was resized after capture. Throws InputError naming
// the file when neither is present.
double exifFocalPixels(const ExifCameraInfo& info, const std::string& path,
                       std::string* source = nullptr);

struct ExifPairOptions {
    double baseline = 0;              // metres between the two centres (> 0)
    std::optional<double> fx;         // pixels; replaces the EXIF focal length of both
    std::optional<double> near, far;  // scene units; absent = left to `predict`
};

// The pair's cameras.json. Both photos must have the same upright size. Without --near/--far
// the file has no depth range, and `predict` estimates it from the pair itself.
CamerasFile exifStereoPair(const std::string& refPath, const std::string& srcPath,
                           const ExifPairOptions& options, std::string* report = nullptr);

}  // namespace lh
