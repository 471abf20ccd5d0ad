// Surface reflection beyond the diffuse albedo: glossy (dielectric, clear-coated) and metallic
// furniture, as in the evaluation rooms.
//
// A surface reflects (1 - F) of the light diffusely with its texture's albedo and F
// specularly about its normal, F the Schlick Fresnel term of the viewing angle. The pictures
// from cameras (ref, src, tgt) show this view-dependent reflection (specular_shading.h). The
// baked light transport, the envmaps and the oracle volume are view-independent: there the
// surface acts as a diffuse one of the same hemispherical reflectance,
// albedo (1 - F_avg) + F_avg, so the energy it sends into the room matches the views on
// average and the lighting volume can represent it exactly.
#pragma once

#include "core/vec.h"

#include <algorithm>
#include <cmath>

namespace lh::synth {

enum class MaterialKind { Diffuse, Glossy, Metal };

struct Material {
    MaterialKind kind = MaterialKind::Diffuse;
    // Reflectance at normal incidence (Schlick's F0), linear RGB in [0, 1): about 0.04 for
    // varnish and plastics, the tint (0.5-0.95) for metals.
    Vec3d f0{0.04, 0.04, 0.04};
    // Half-angle of the cone the mirror direction is spread over, radians (0: a mirror).
    double roughness = 0;

    bool isSpecular() const { return kind != MaterialKind::Diffuse; }
};

// Schlick's approximation of the Fresnel reflectance, per channel; cosTheta = n . w_out.
inline Vec3d fresnelSchlick(const Vec3d& f0, double cosTheta) {
    const double m = std::pow(1.0 - std::clamp(cosTheta, 0.0, 1.0), 5.0);
    return f0 + (Vec3d(1.0) - f0) * m;
}

// Schlick's term averaged over the cosine-weighted hemisphere: 2 int (1 - mu)^5 mu dmu = 1/21.
inline Vec3d averageFresnel(const Vec3d& f0) { return f0 + (Vec3d(1.0) - f0) * (1.0 / 21.0); }

// The albedo of the diffuse surface that reflects as much light in total (see above).
inline Vec3d viewIndependentAlbedo(const Material& m, const Vec3d& albedo) {
    if (!m.isSpecular()) return albedo;
    const Vec3d f = averageFresnel(m.f0);
    Vec3d out;
    for (int c = 0; c < 3; ++c) out[c] = albedo[c] * (1.0 - f[c]) + f[c];
    return out;
}

}  // namespace lh::synth
