#include "image/image_orientation.h"

#include <libexif/exif-data.h>

#include <memory>

namespace lh {

namespace {

struct ExifDataDeleter {
    void operator()(ExifData* d) const { exif_data_unref(d); }
};

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
    return uprightImage(stored.width, stored.height, orientation, [&](int sx, int sy, float* to) {
        const float* from = stored.at(sx, sy);
        to[0] = from[0];
        to[1] = from[1];
        to[2] = from[2];
    });
}

}  // namespace lh
