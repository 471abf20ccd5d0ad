#include "houdini_export/dcc_convention.h"

#include "core/errors.h"

#include <algorithm>
#include <cctype>

namespace lh {

std::string dccLevelFileName(int level) { return "level_" + std::to_string(level) + ".vdb"; }

DccConvention dccConvention(Dcc dcc) {
    DccConvention c;
    c.dcc = dcc;
    if (dcc == Dcc::Blender) {
        c.name = "blender";
        // Rows give the DCC axes in lighthouse coordinates: X = x, Y = z, Z = -y.
        c.worldToDcc = Mat3d(1, 0, 0,  //
                             0, 0, 1,  //
                             0, -1, 0);
        c.axesText = "X = x, Y = z, Z = -y (Z-up; lighthouse forward +z is Blender +Y)";
        c.colorGrid = "color";
        c.splitEmission = true;
        c.indexShift = -0.5;
    } else {
        c.name = "houdini";
        c.worldToDcc = Mat3d(1, 0, 0,   //
                             0, -1, 0,  //
                             0, 0, -1);
        c.axesText = "X = x, Y = -y, Z = -z (Y-up; lighthouse forward +z is Houdini -Z)";
        c.colorGrid = "Cd";
    }
    return c;
}

Dcc parseDcc(const std::string& text, const std::string& what) {
    std::string t = text;
    std::transform(t.begin(), t.end(), t.begin(),
                   [](unsigned char ch) { return char(std::tolower(ch)); });
    if (t == "blender") return Dcc::Blender;
    if (t == "houdini") return Dcc::Houdini;
    throw InputError(what + ": expected 'blender' or 'houdini', got '" + text + "'");
}

}  // namespace lh
