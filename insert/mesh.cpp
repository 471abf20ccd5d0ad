#include "insert/mesh.h"

#include "core/errors.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

namespace lh {

namespace {

// tinyobjloader reads a coordinate it cannot parse ("nan", "inf", "1e999") as 0 or as an
// infinity without a word, which would move the vertex silently. Every "v" line's first
// three coordinates must be finite numbers.
void requireFiniteVertices(const std::string& path) {
    std::ifstream file(path);
    std::string line;
    for (long number = 1; std::getline(file, line); ++number) {
        if (line.size() < 2 || line[0] != 'v' || (line[1] != ' ' && line[1] != '\t')) continue;
        std::istringstream fields(line.substr(2));
        std::string token;
        for (int axis = 0; axis < 3 && fields >> token; ++axis) {
            char* end = nullptr;
            const double value = std::strtod(token.c_str(), &end);
            if (end == token.c_str() || *end != '\0' || !std::isfinite(value))
                throw FileError("mesh '" + path + "' line " + std::to_string(number) +
                                ": vertex coordinate '" + token + "' is not a finite number");
        }
    }
}

TriangleMesh uvSphere(int around, int polar) {
    TriangleMesh m;
    for (int i = 0; i <= polar; ++i)
        for (int j = 0; j <= around; ++j) {
            const double v = M_PI * i / polar, u = 2 * M_PI * j / around;
            const Vec3d n(std::sin(v) * std::cos(u), -std::cos(v), std::sin(v) * std::sin(u));
            m.positions.push_back(n);
            m.normals.push_back(n);
        }
    for (int i = 0; i < polar; ++i)
        for (int j = 0; j < around; ++j) {
            const uint32_t a = i * (around + 1) + j, b = a + 1, c = a + around + 1, d = c + 1;
            m.indices.insert(m.indices.end(), {a, c, b, b, c, d});
        }
    return m;
}

TriangleMesh cube() {
    TriangleMesh m;
    for (int axis = 0; axis < 3; ++axis)
        for (int side = -1; side <= 1; side += 2) {
            Vec3d n(0.0), t(0.0), b(0.0);
            n[axis] = side;
            t[(axis + 1) % 3] = 1;
            b[(axis + 2) % 3] = 1;
            if (t.cross(b).dot(n) < 0) std::swap(t, b);  // counter-clockwise seen from outside
            const uint32_t base = uint32_t(m.positions.size());
            for (int c = 0; c < 4; ++c) {
                const double s = (c == 1 || c == 2) ? 1 : -1, r = (c >= 2) ? 1 : -1;
                m.positions.push_back(n + t * s + b * r);
                m.normals.push_back(n);
            }
            m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
        }
    return m;
}

TriangleMesh torus(double major, double minor, int around, int tube) {
    TriangleMesh m;
    for (int i = 0; i <= around; ++i)
        for (int j = 0; j <= tube; ++j) {
            const double u = 2 * M_PI * i / around, v = 2 * M_PI * j / tube;
            const Vec3d ring(std::cos(u), 0, std::sin(u));
            const Vec3d n = ring * std::cos(v) + Vec3d(0, std::sin(v), 0);
            m.positions.push_back(ring * major + n * minor);
            m.normals.push_back(n);
        }
    for (int i = 0; i < around; ++i)
        for (int j = 0; j < tube; ++j) {
            const uint32_t a = i * (tube + 1) + j, b = a + 1, c = a + tube + 1, d = c + 1;
            m.indices.insert(m.indices.end(), {a, b, c, b, d, c});
        }
    return m;
}

TriangleMesh cylinder(int around) {
    TriangleMesh m;
    // Side (smooth normals), then two flat caps with their own vertices.
    for (int side = 0; side < 2; ++side)
        for (int j = 0; j <= around; ++j) {
            const double u = 2 * M_PI * j / around;
            const Vec3d radial(std::cos(u), 0, std::sin(u));
            m.positions.push_back(radial + Vec3d(0, side ? 1 : -1, 0));
            m.normals.push_back(radial);
        }
    for (int j = 0; j < around; ++j) {
        const uint32_t a = j, b = j + 1, c = a + around + 1, d = b + around + 1;
        m.indices.insert(m.indices.end(), {a, c, b, b, c, d});
    }
    for (int side = 0; side < 2; ++side) {
        const double y = side ? 1 : -1;
        const uint32_t centre = uint32_t(m.positions.size());
        m.positions.push_back(Vec3d(0, y, 0));
        m.normals.push_back(Vec3d(0, y, 0));
        for (int j = 0; j <= around; ++j) {
            const double u = 2 * M_PI * j / around;
            m.positions.push_back(Vec3d(std::cos(u), y, std::sin(u)));
            m.normals.push_back(Vec3d(0, y, 0));
        }
        for (int j = 0; j < around; ++j) {
            const uint32_t a = centre + 1 + j, b = a + 1;
            if (side)
                m.indices.insert(m.indices.end(), {centre, a, b});
            else
                m.indices.insert(m.indices.end(), {centre, b, a});
        }
    }
    return m;
}

}  // namespace

void TriangleMesh::normalise() {
    Vec3d lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (const Vec3d& p : positions) {
        lo = openvdb::math::minComponent(lo, p);
        hi = openvdb::math::maxComponent(hi, p);
    }
    const Vec3d centre = (lo + hi) * 0.5;
    double radius = 0;
    for (const Vec3d& p : positions) radius = std::max(radius, (p - centre).length());
    if (!(radius > 0)) throw InputError("mesh has no extent");
    for (Vec3d& p : positions) p = (p - centre) / radius;
}

void TriangleMesh::transform(double scale, const Mat3d& rotation, const Vec3d& translation) {
    for (Vec3d& p : positions) p = rotation * (p * scale) + translation;
    for (Vec3d& n : normals) n = (rotation * n).unitSafe();
}

void TriangleMesh::computeNormals() {
    normals.assign(positions.size(), Vec3d(0.0));
    for (std::size_t t = 0; t < indices.size(); t += 3) {
        const Vec3d& a = positions[indices[t]];
        const Vec3d n = (positions[indices[t + 1]] - a).cross(positions[indices[t + 2]] - a);
        for (int k = 0; k < 3; ++k) normals[indices[t + k]] += n;  // area-weighted
    }
    for (Vec3d& n : normals) n = n.unitSafe();
}

TriangleMesh builtinMesh(const std::string& name) {
    TriangleMesh m;
    if (name == "sphere")
        m = uvSphere(96, 48);
    else if (name == "cube")
        m = cube();
    else if (name == "torus")
        m = torus(1.0, 0.4, 96, 48);
    else if (name == "cylinder")
        m = cylinder(96);
    else
        throw InputError("unknown built-in object '" + name +
                         "' (sphere, cube, torus, cylinder, or a .obj file)");
    m.normalise();
    return m;
}

TriangleMesh loadObj(const std::string& path) {
    if (!std::filesystem::exists(path)) throw FileError("mesh file '" + path + "' does not exist");
    requireFiniteVertices(path);
    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(path, config))
        throw FileError("cannot read mesh '" + path + "': " + reader.Error());
    const auto& attrib = reader.GetAttrib();
    TriangleMesh m;
    for (std::size_t i = 0; i + 2 < attrib.vertices.size(); i += 3)
        m.positions.push_back(
            Vec3d(attrib.vertices[i], attrib.vertices[i + 1], attrib.vertices[i + 2]));
    for (const auto& shape : reader.GetShapes())
        for (const auto& index : shape.mesh.indices) {
            if (index.vertex_index < 0 || std::size_t(index.vertex_index) >= m.positions.size())
                throw FileError("mesh '" + path + "' refers to a vertex that does not exist");
            m.indices.push_back(uint32_t(index.vertex_index));
        }
    if (m.indices.size() < 3) throw InputError("mesh '" + path + "' has no triangles");
    for (const Vec3d& p : m.positions)
        if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z()))
            throw FileError("mesh '" + path + "' has a non-finite vertex");
    m.computeNormals();
    m.normalise();
    return m;
}

TriangleMesh loadMesh(const std::string& nameOrPath) {
    if (nameOrPath.size() > 4 && nameOrPath.substr(nameOrPath.size() - 4) == ".obj")
        return loadObj(nameOrPath);
    return builtinMesh(nameOrPath);
}

Mat3d rotationFromDegrees(const Vec3d& degrees) {
    const Vec3d r = degrees * (M_PI / 180.0);
    const double cx = std::cos(r.x()), sx = std::sin(r.x()), cy = std::cos(r.y()),
                 sy = std::sin(r.y()), cz = std::cos(r.z()), sz = std::sin(r.z());
    const Mat3d rx(1.0, 0.0, 0.0, 0.0, cx, -sx, 0.0, sx, cx);
    const Mat3d ry(cy, 0.0, sy, 0.0, 1.0, 0.0, -sy, 0.0, cy);
    const Mat3d rz(cz, -sz, 0.0, sz, cz, 0.0, 0.0, 0.0, 1.0);
    return rz * ry * rx;
}

}  // namespace lh
