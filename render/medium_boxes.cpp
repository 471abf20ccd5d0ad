#include "render/medium_boxes.h"

#include <algorithm>
#include <cmath>

namespace lh {

namespace {

// The parts of `box` that no domain in finerDomains[first..] covers, appended to `out`.
void appendVisibleParts(const MediumBox& box, const std::vector<MediumBox>& finerDomains,
                        std::size_t first, std::vector<MediumBox>& out) {
    for (std::size_t j = first; j < finerDomains.size(); ++j) {
        const MediumBox& d = finerDomains[j];
        int uncovered = -1, uncoveredCount = 0;  // axes along which d does not span the box
        bool disjoint = false;
        for (int a = 0; a < 3; ++a) {
            disjoint |= d.hi[a] <= box.lo[a] || d.lo[a] >= box.hi[a];
            if (!(d.lo[a] <= box.lo[a] && d.hi[a] >= box.hi[a])) uncovered = a, ++uncoveredCount;
        }
        if (disjoint || uncoveredCount > 1) continue;
        if (uncoveredCount == 0) return;  // wholly hidden
        const int a = uncovered;
        if (box.lo[a] < d.lo[a]) {
            MediumBox below = box;
            below.hi[a] = d.lo[a];
            appendVisibleParts(below, finerDomains, j + 1, out);
        }
        if (box.hi[a] > d.hi[a]) {
            MediumBox above = box;
            above.lo[a] = d.hi[a];
            appendVisibleParts(above, finerDomains, j + 1, out);
        }
        return;
    }
    out.push_back(box);
}

// An axis-aligned level's index box [lo, hi] in scene units.
MediumBox worldBox(const RenderLevel& level, const double lo[3], const double hi[3]) {
    MediumBox box{};
    for (int a = 0; a < 3; ++a) {
        const double w0 = level.indexToWorld(a, a) * (lo[a] - level.indexOffset[a]);
        const double w1 = level.indexToWorld(a, a) * (hi[a] - level.indexOffset[a]);
        box.lo[a] = std::min(w0, w1), box.hi[a] = std::max(w0, w1);
    }
    return box;
}

}  // namespace

bool boundMedium(const std::vector<RenderLevel>& levels, std::vector<MediumBox>& boxes) {
    constexpr int n = RenderLevel::kBrick;
    for (const RenderLevel& level : levels)
        if (!level.axisAligned && !level.cellBoxes.empty()) return false;
    // Domains of the levels (outer voxel faces), narrowed by a millionth of a voxel so that
    // rounding cannot hide medium they do not cover. A level whose axes are not the world's
    // holds no medium here (above); its empty box hides nothing, which is safe.
    std::vector<MediumBox> domains;
    for (const RenderLevel& level : levels) {
        MediumBox d = worldBox(level, level.domainLo.asPointer(), level.domainHi.asPointer());
        const double margin = 1e-6 * std::cbrt(level.voxelVolume);
        for (int a = 0; a < 3; ++a) d.lo[a] += margin, d.hi[a] -= margin;
        domains.push_back(level.axisAligned ? d : MediumBox{});
    }
    for (std::size_t k = 0; k < levels.size(); ++k) {
        const RenderLevel& level = levels[k];
        if (level.cellBoxes.empty()) continue;
        const std::vector<MediumBox> finerDomains(domains.begin() + std::ptrdiff_t(k) + 1,
                                                  domains.end());
        const double margin = 1e-6 * std::cbrt(level.voxelVolume);
        for (int bz = 0; bz < level.brickCount[2]; ++bz)
            for (int by = 0; by < level.brickCount[1]; ++by)
                for (int bx = 0; bx < level.brickCount[0]; ++bx) {
                    const int b = level.brickIndex(bx, by, bz);
                    if (b < 0) continue;
                    const RenderLevel::CellBox& cells = level.cellBox(b);
                    const int brick[3] = {bx, by, bz};
                    // Lattice point k of the level is index coordinate latticeOrigin + k; cell
                    // i of a brick spans lattice points [i, i + 1].
                    double lo[3], hi[3];
                    bool empty = false;
                    for (int a = 0; a < 3; ++a) {
                        empty |= cells.lo[a] >= cells.hi[a];
                        lo[a] = level.latticeOrigin[a] + n * brick[a] + cells.lo[a];
                        hi[a] = level.latticeOrigin[a] + n * brick[a] + cells.hi[a];
                    }
                    if (empty) continue;
                    MediumBox box = worldBox(level, lo, hi);
                    for (int a = 0; a < 3; ++a) box.lo[a] -= margin, box.hi[a] += margin;
                    appendVisibleParts(box, finerDomains, 0, boxes);
                }
    }
    return true;
}

}  // namespace lh
