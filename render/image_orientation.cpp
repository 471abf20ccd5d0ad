#include "render/image_orientation.h"

#include <libexif/exif-data.h>

#include <memory>

namespace lh {

namespace {

struct ExifDataDeleter {
    void operator()(ExifData* d) const { exif_data_unref(d); }
};

// The stored pixel shown at upright (x, y), for a stored image of w x h.
void storedPixelOf(int orientation, int x, int y, int w, int h, int& sx, int& sy) {
    switch (orientation) {
    case 2: sx = w - 1 - x; sy = y; break;
    case 3: sx = w - 1 - x; sy = h - 1 - y; break;
    case 4: sx = x; sy = h - 1 - y; break;
    case 5: sx = y; sy = x; break;
    case 6: sx = y; sy = h - 1 - x; break;
    case 7: sx = w - 1 - y; sy = h - 1 - x; break;
    case 8: sx = w - 1 - y; sy = x; break;
    default: sx = x; sy = y; break;
    }
}

}  // namespace

int exifOrientation(const std::string& path) {
    std::unique_ptr<ExifData, ExifDataDeleter> data(exif_data_new_from_file(path.c_str()));
    if (!data) return 1;
    ExifEntry* e = exif_content_get_entry(data->ifd[EXIF_IFD_0], EXIF_TAG_ORIENTATION);
    if (!e || !e->data || e->format != EXIF_FORMAT_SHORT || e->size < 2) return 1;
    const int value = exif_get_short(e->data, exif_data_get_byte_order(data.get()));
    return value >= 1 && value <= 8 ? value : 1;
}

ImageRGB applyOrientation(const ImageRGB& stored, int orientation) {
    if (orientation < 2 || orientation > 8) return stored;
    const bool swapAxes = orientation >= 5;
    ImageRGB upright(swapAxes ? stored.height : stored.width, swapAxes ? stored.width : stored.height);
    for (int y = 0; y < upright.height; ++y)
        for (int x = 0; x < upright.width; ++x) {
            int sx = 0, sy = 0;
            storedPixelOf(orientation, x, y, stored.width, stored.height, sx, sy);
            const float* from = stored.at(sx, sy);
            float* to = upright.at(x, y);
            to[0] = from[0];
            to[1] = from[1];
            to[2] = from[2];
        }
    return upright;
}

}  // namespace lh
