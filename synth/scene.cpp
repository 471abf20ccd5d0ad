#include "synth/scene.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lh::synth {

namespace {

double fract(double x) { return x - std::floor(x); }

// Integer lattice hash -> [0, 1).
double latticeValue(int x, int y, int z, uint32_t seed) {
    uint32_t h = seed * 0x9E3779B9u;
    h ^= uint32_t(x) * 0x85EBCA6Bu;
    h = (h << 13) | (h >> 19);
    h ^= uint32_t(y) * 0xC2B2AE35u;
    h = (h << 11) | (h >> 21);
    h ^= uint32_t(z) * 0x27D4EB2Fu;
    h ^= h >> 16;
    h *= 0x7FEB352Du;
    h ^= h >> 15;
    return (h & 0xFFFFFF) / double(0x1000000);
}

// Smooth value noise in [0, 1].
double valueNoise(const Vec3d& p, uint32_t seed) {
    const int x = int(std::floor(p.x())), y = int(std::floor(p.y())), z = int(std::floor(p.z()));
    const auto smooth = [](double t) { return t * t * (3 - 2 * t); };
    const double fx = smooth(p.x() - x), fy = smooth(p.y() - y), fz = smooth(p.z() - z);
    double result = 0;
    for (int c = 0; c < 8; ++c) {
        const int dx = c & 1, dy = (c >> 1) & 1, dz = c >> 2;
        const double w = (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy) * (dz ? fz : 1 - fz);
        result += w * latticeValue(x + dx, y + dy, z + dz, seed);
    }
    return result;
}

Vec3d mix(const Vec3d& a, const Vec3d& b, double t) { return a * (1 - t) + b * t; }

// Offset of pattern lattices from local coordinates, so that faces lying on whole multiples
// of the period do not flicker between two colours.
constexpr double kPatternShift = 0.37;

SurfacePoint makePoint(const Primitive& p, int index, int face, double u, double v,
                       const Vec3d& local, const Vec3d& localNormal) {
    SurfacePoint s;
    s.primitive = index;
    s.face = face;
    s.u = u;
    s.v = v;
    s.position = p.toWorld(local);
    const Vec3d n = p.rotation * localNormal;
    s.normal = (p.inverted ? -n : n).unitSafe();
    return s;
}

// Running-bond brick (see kBrickRowHeight): colorA in bricks, colorB on mortar lines.
Vec3d brickAlbedo(const Texture& t, const Vec3d& q, const Vec3d& normal) {
    // The face's plane: rows run across the vertical axis y on walls and on box sides, across
    // z on floors, ceilings and tops; bricks run along the other in-plane axis.
    const Vec3d n(std::abs(normal.x()), std::abs(normal.y()), std::abs(normal.z()));
    const int axis = n.y() >= n.x() && n.y() >= n.z() ? 1 : (n.x() >= n.z() ? 0 : 2);
    const double rowCoordinate = axis == 1 ? q.z() : q.y();
    const double alongCoordinate = axis == 0 ? q.z() : q.x();
    const double rowF = rowCoordinate / kBrickRowHeight;
    const int row = int(std::floor(rowF));
    const double inRow = fract(rowF) * kBrickRowHeight;  // brick-lengths from the row's joint
    const double alongF = alongCoordinate + ((row & 1) ? 0.5 : 0.0);
    const int column = int(std::floor(alongF));
    const double inBrick = fract(alongF);
    const double m = kMortarWidth / 2;
    if (inRow < m || inRow > kBrickRowHeight - m || inBrick < m || inBrick > 1 - m) return t.colorB;
    return t.colorA * (0.8 + 0.2 * latticeValue(column, row, axis, t.noiseSeed));
}

}  // namespace

Vec3d Texture::albedo(const Vec3d& local, const Vec3d& localNormal) const {
    const Vec3d q = local / scale + Vec3d(kPatternShift);
    switch (kind) {
        case TextureKind::Plain:
            return colorA;
        case TextureKind::Checker: {
            const int parity = int(std::floor(q.x()) + std::floor(q.y()) + std::floor(q.z()));
            return (parity & 1) ? colorB : colorA;
        }
        case TextureKind::Stripes:
            return fract(q.x()) < 0.5 ? colorA : colorB;
        case TextureKind::Noise: {
            const double n =
                0.65 * valueNoise(q * 2.0, noiseSeed) + 0.35 * valueNoise(q * 6.0, noiseSeed + 1);
            return mix(colorA, colorB, n);
        }
        case TextureKind::Wood: {
            const double ring = std::sqrt(q.x() * q.x() + q.z() * q.z()) * 3.0 +
                                1.5 * valueNoise(q * 1.5, noiseSeed);
            const double t = fract(ring);
            return mix(colorA, colorB, std::clamp((t - 0.3) / 0.4, 0.0, 1.0));
        }
        case TextureKind::Brick:
            return brickAlbedo(*this, q, localNormal);
        case TextureKind::Bands:
            return mix(colorA, colorB,
                       0.5 + 0.5 * std::sin(2 * M_PI * (q.x() + q.y() + q.z()) / std::sqrt(3.0)));
        case TextureKind::Rings:
            return mix(colorA, colorB, 0.5 + 0.5 * std::sin(2 * M_PI * q.length()));
    }
    return colorA;
}

int faceCount(const Primitive& p) {
    switch (p.shape) {
        case Shape::Box:
            return 6;
        case Shape::Cylinder:
            return 3;
        default:
            return 1;
    }
}

FaceRange faceRange(const Primitive& p, int face) {
    switch (p.shape) {
        case Shape::Box: {
            const int a = face / 2, b = (a + 1) % 3, c = (a + 2) % 3;
            return {-p.half[b], p.half[b], -p.half[c], p.half[c], 1.0, 1.0, false};
        }
        case Shape::Sphere:
            return {-M_PI, M_PI, 0.0, M_PI, p.half.x(), p.half.x(), true};
        case Shape::Cylinder:
            if (face == 0) return {-M_PI, M_PI, -p.half.y(), p.half.y(), p.half.x(), 1.0, true};
            return {-p.half.x(), p.half.x(), -p.half.x(), p.half.x(), 1.0, 1.0, false};
        case Shape::Quad:
            return {-p.half.x(), p.half.x(), -p.half.y(), p.half.y(), 1.0, 1.0, false};
    }
    return {0, 0, 0, 0, 1, 1, false};
}

SurfacePoint surfaceAt(const Primitive& p, int index, int face, double u, double v) {
    switch (p.shape) {
        case Shape::Box: {
            const int a = face / 2, b = (a + 1) % 3, c = (a + 2) % 3;
            const double side = (face % 2) ? 1.0 : -1.0;
            Vec3d local(0.0), normal(0.0);
            local[a] = side * p.half[a];
            local[b] = u;
            local[c] = v;
            normal[a] = side;
            return makePoint(p, index, face, u, v, local, normal);
        }
        case Shape::Sphere: {
            const double r = p.half.x();
            const Vec3d n(std::sin(v) * std::cos(u), std::cos(v), std::sin(v) * std::sin(u));
            return makePoint(p, index, face, u, v, n * r, n);
        }
        case Shape::Cylinder: {
            const double r = p.half.x(), h = p.half.y();
            if (face == 0) {
                const Vec3d radial(std::cos(u), 0.0, std::sin(u));
                return makePoint(p, index, face, u, v, radial * r + Vec3d(0, v, 0), radial);
            }
            // Caps are parameterised over their bounding square; corners fold onto the rim.
            const double y = face == 1 ? -h : h, rho = std::hypot(u, v),
                         fold = rho > r ? r / rho : 1.0;
            return makePoint(p, index, face, u, v, Vec3d(u * fold, y, v * fold),
                             Vec3d(0, face == 1 ? -1 : 1, 0));
        }
        case Shape::Quad:
            return makePoint(p, index, face, u, v, Vec3d(u, v, 0.0), Vec3d(0, 0, 1));
    }
    return {};
}

SurfacePoint nearestSurfacePoint(const Primitive& p, int index, const Vec3d& world) {
    const Vec3d l = p.toLocal(world);
    switch (p.shape) {
        case Shape::Box: {
            // On a convex shape the nearest surface point is the nearest of the faces'
            // clamped projections.
            SurfacePoint best;
            double bestDistance = std::numeric_limits<double>::infinity();
            for (int face = 0; face < 6; ++face) {
                const int a = face / 2, b = (a + 1) % 3, c = (a + 2) % 3;
                const double u = std::clamp(l[b], -p.half[b], p.half[b]);
                const double v = std::clamp(l[c], -p.half[c], p.half[c]);
                Vec3d q(0.0);
                q[a] = ((face % 2) ? 1.0 : -1.0) * p.half[a];
                q[b] = u;
                q[c] = v;
                const double d = (q - l).lengthSqr();
                if (d < bestDistance) bestDistance = d, best = surfaceAt(p, index, face, u, v);
            }
            return best;
        }
        case Shape::Sphere: {
            const Vec3d n = l.lengthSqr() > 0 ? l.unit() : Vec3d(0, -1, 0);
            return surfaceAt(p, index, 0, std::atan2(n.z(), n.x()),
                             std::acos(std::clamp(n.y(), -1.0, 1.0)));
        }
        case Shape::Cylinder: {
            const double r = p.half.x(), h = p.half.y();
            const double rho = std::sqrt(l.x() * l.x() + l.z() * l.z());
            const double angle = rho > 0 ? std::atan2(l.z(), l.x()) : 0.0;
            const double y = std::clamp(l.y(), -h, h);
            const Vec3d side(r * std::cos(angle), y, r * std::sin(angle));
            const double capScale = rho > r ? r / rho : 1.0;
            const Vec3d capInPlane(l.x() * capScale, 0.0, l.z() * capScale);
            const Vec3d bottom = capInPlane + Vec3d(0, -h, 0), top = capInPlane + Vec3d(0, h, 0);
            const double dSide = (side - l).lengthSqr(), dBottom = (bottom - l).lengthSqr(),
                         dTop = (top - l).lengthSqr();
            if (dSide <= dBottom && dSide <= dTop) return surfaceAt(p, index, 0, angle, y);
            return dBottom < dTop ? surfaceAt(p, index, 1, bottom.x(), bottom.z())
                                  : surfaceAt(p, index, 2, top.x(), top.z());
        }
        case Shape::Quad:
            return surfaceAt(p, index, 0, std::clamp(l.x(), -p.half.x(), p.half.x()),
                             std::clamp(l.y(), -p.half.y(), p.half.y()));
    }
    return {};
}

double signedDistance(const Primitive& p, const Vec3d& world) {
    const Vec3d l = p.toLocal(world);
    double d = std::numeric_limits<double>::infinity();
    switch (p.shape) {
        case Shape::Box: {
            const Vec3d q(std::abs(l.x()) - p.half.x(), std::abs(l.y()) - p.half.y(),
                          std::abs(l.z()) - p.half.z());
            const Vec3d outside(std::max(q.x(), 0.0), std::max(q.y(), 0.0), std::max(q.z(), 0.0));
            d = outside.length() + std::min(std::max(q.x(), std::max(q.y(), q.z())), 0.0);
            break;
        }
        case Shape::Sphere:
            d = l.length() - p.half.x();
            break;
        case Shape::Cylinder: {
            const double dr = std::sqrt(l.x() * l.x() + l.z() * l.z()) - p.half.x();
            const double dy = std::abs(l.y()) - p.half.y();
            d = std::min(std::max(dr, dy), 0.0) +
                std::sqrt(std::pow(std::max(dr, 0.0), 2) + std::pow(std::max(dy, 0.0), 2));
            break;
        }
        case Shape::Quad:
            return std::numeric_limits<double>::infinity();  // thin, never solid
    }
    return p.inverted ? -d : d;
}

double surfaceArea(const Primitive& p) {
    const Vec3d h = p.half;
    switch (p.shape) {
        case Shape::Box:
            return 8.0 * (h.x() * h.y() + h.y() * h.z() + h.z() * h.x());
        case Shape::Sphere:
            return 4.0 * M_PI * h.x() * h.x();
        case Shape::Cylinder:
            return 4.0 * M_PI * h.x() * h.y() + 2.0 * M_PI * h.x() * h.x();
        case Shape::Quad:
            return 4.0 * h.x() * h.y();
    }
    return 0;
}

double Scene::distanceToSolid(const Vec3d& p) const {
    double d = std::numeric_limits<double>::infinity();
    for (const auto& prim : primitives)
        if (!prim.isDecal()) d = std::min(d, signedDistance(prim, p));
    return d;
}

int Scene::solidAt(const Vec3d& p) const {
    for (std::size_t i = 0; i < primitives.size(); ++i)
        if (!primitives[i].isDecal() && signedDistance(primitives[i], p) < 0) return int(i);
    return -1;
}

std::vector<int> Scene::emitters() const {
    std::vector<int> out;
    for (std::size_t i = 0; i < primitives.size(); ++i)
        if (primitives[i].isEmitter()) out.push_back(int(i));
    return out;
}

}  // namespace lh::synth
