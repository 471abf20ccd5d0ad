// Materials of inserted objects and their importance sampling. All are energy-conserving
// reflectors lit only by what their rays see (no emission).
//   mirror              perfect specular reflection (one ray)
//   glossy:ROUGHNESS    GGX microfacet metal, white, alpha = ROUGHNESS^2, sampled by the
//                       distribution of visible-ish normals (Walter et al. 2007)
//   diffuse:R,G,B       Lambertian with linear albedo R,G,B in [0, 1], cosine-sampled
#pragma once

#include "core/vec.h"

#include <string>

namespace lh {

struct Material {
    enum class Kind { Mirror, Glossy, Diffuse };
    Kind kind = Kind::Mirror;
    double roughness = 0.2;       // glossy only, in (0, 1]
    Vec3d albedo{1.0, 1.0, 1.0};  // diffuse albedo (linear) or specular tint

    // "mirror", "glossy:0.3", "diffuse:0.8,0.2,0.2". Throws InputError.
    static Material parse(const std::string& text);
};

struct MaterialSample {
    Vec3d direction;  // unit, leaving the surface
    Vec3d weight;     // BRDF * cos / pdf: multiply the incoming radiance by it
};

// Samples an outgoing direction at a surface with unit normal n (facing the viewer) for a
// ray arriving along `incoming` (unit, towards the surface). u1, u2 uniform in [0, 1).
MaterialSample sampleMaterial(const Material& m, const Vec3d& n, const Vec3d& incoming, double u1,
                              double u2);

}  // namespace lh
