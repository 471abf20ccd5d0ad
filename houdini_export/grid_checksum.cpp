#include "houdini_export/grid_checksum.h"

#include <cstdint>
#include <cstdio>
#include <cstring>

namespace lh {

namespace {

// SplitMix64's mixing step: every input bit affects every output bit.
std::uint64_t mix(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

std::uint64_t bitsOf(float v) {
    if (v == 0.f) v = 0.f;  // -0 and +0 render alike
    std::uint32_t b;
    std::memcpy(&b, &v, 4);
    return b;
}

bool isZero(float v) { return v == 0.f; }
bool isZero(const openvdb::Vec3s& v) { return v[0] == 0.f && v[1] == 0.f && v[2] == 0.f; }

std::uint64_t hashValue(std::uint64_t h, float v) { return mix(h ^ bitsOf(v)); }
std::uint64_t hashValue(std::uint64_t h, const openvdb::Vec3s& v) {
    for (int c = 0; c < 3; ++c) h = mix(h ^ bitsOf(v[c]));
    return h;
}

std::uint64_t hashVoxel(const openvdb::Coord& ijk, std::uint64_t valueHashSeed) {
    std::uint64_t h = valueHashSeed;
    for (int a = 0; a < 3; ++a) h = mix(h ^ std::uint64_t(std::uint32_t(ijk[a])));
    return h;
}

template <typename GridT>
std::string checksumOf(const GridT& grid) {
    std::uint64_t sum = 0, count = 0;
    for (auto it = grid.cbeginValueOn(); it; ++it) {
        const auto value = *it;
        if (isZero(value)) continue;
        const std::uint64_t valueHash = hashValue(0x6c69676874686f75ull, value);
        if (it.isVoxelValue()) {
            sum += hashVoxel(it.getCoord(), valueHash), ++count;
        } else {
            const openvdb::CoordBBox box = it.getBoundingBox();
            for (auto ijk = box.beginXYZ(); ijk; ++ijk) sum += hashVoxel(*ijk, valueHash), ++count;
        }
    }
    char text[17];
    std::snprintf(text, sizeof text, "%016llx",
                  static_cast<unsigned long long>(mix(sum ^ mix(count))));
    return text;
}

}  // namespace

std::string gridChecksum(const openvdb::GridBase& grid) {
    if (const auto* g = dynamic_cast<const openvdb::FloatGrid*>(&grid)) return checksumOf(*g);
    if (const auto* g = dynamic_cast<const openvdb::Vec3SGrid*>(&grid)) return checksumOf(*g);
    return "";
}

}  // namespace lh
