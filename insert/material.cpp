#include "insert/material.h"

#include "core/errors.h"
#include "core/sampling.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace lh {

namespace {

Vec3d reflect(const Vec3d& d, const Vec3d& n) { return d - n * (2 * d.dot(n)); }

// Smith G1 for GGX.
double smithG1(double cosTheta, double alpha) {
    const double c2 = cosTheta * cosTheta;
    return 2.0 / (1.0 + std::sqrt(1.0 + alpha * alpha * (1.0 - c2) / std::max(c2, 1e-12)));
}

}  // namespace

Material Material::parse(const std::string& text) {
    Material m;
    const auto colon = text.find(':');
    const std::string kind = text.substr(0, colon),
                      args = colon == std::string::npos ? "" : text.substr(colon + 1);
    const auto fail = [&]() -> Material {
        throw InputError("material '" + text +
                         "': expected mirror, glossy:ROUGHNESS (0-1] or diffuse:R,G,B (0-1)");
    };
    if (kind == "mirror" && args.empty()) {
        m.kind = Kind::Mirror;
        return m;
    }
    if (kind == "glossy") {
        m.kind = Kind::Glossy;
        std::size_t used = 0;
        try {
            m.roughness = std::stod(args, &used);
        } catch (const std::exception&) {
            return fail();
        }
        if (used != args.size() || !(m.roughness > 0 && m.roughness <= 1)) return fail();
        return m;
    }
    if (kind == "diffuse") {
        m.kind = Kind::Diffuse;
        std::string s = args;
        std::replace(s.begin(), s.end(), ',', ' ');
        std::istringstream in(s);
        double r, g, b;
        std::string rest;
        if (!(in >> r >> g >> b) || (in >> rest)) return fail();
        for (double v : {r, g, b})
            if (!(v >= 0 && v <= 1)) return fail();
        m.albedo = Vec3d(r, g, b);
        return m;
    }
    return fail();
}

MaterialSample sampleMaterial(const Material& m, const Vec3d& n, const Vec3d& incoming, double u1,
                              double u2) {
    switch (m.kind) {
        case Material::Kind::Mirror:
            return {reflect(incoming, n).unit(), m.albedo};
        case Material::Kind::Diffuse: {
            // Cosine-weighted: BRDF * cos / pdf = albedo.
            return {cosineDirection(n, u1, u2), m.albedo};
        }
        case Material::Kind::Glossy: {
            // GGX normal sampling: pdf(h) = D(h) cos(h); for reflection the weight is
            // F G (v.h) / ((n.v)(n.h)) with F = tint (a white metal).
            Vec3d t, b;
            tangentFrame(n, t, b);
            const double alpha = m.roughness * m.roughness;
            const double tan2 = alpha * alpha * u1 / std::max(1e-12, 1 - u1);
            const double cosH = 1 / std::sqrt(1 + tan2),
                         sinH = std::sqrt(std::max(0.0, 1 - cosH * cosH));
            const double phi = 2 * M_PI * u2;
            const Vec3d h =
                (t * (sinH * std::cos(phi)) + b * (sinH * std::sin(phi)) + n * cosH).unit();
            const Vec3d v = -incoming;
            const Vec3d l = reflect(incoming, h).unit();
            const double nl = n.dot(l), nv = n.dot(v), vh = v.dot(h), nh = n.dot(h);
            if (nl <= 0 || nv <= 0 || vh <= 0) return {l, Vec3d(0.0)};
            const double g = smithG1(nv, alpha) * smithG1(nl, alpha);
            return {l, m.albedo * (g * vh / (nv * nh))};
        }
    }
    return {n, Vec3d(0.0)};
}

}  // namespace lh
