// Triangle meshes of objects inserted into photographs: OBJ files (tinyobjloader) or built-in
// primitives. Every mesh is centred on its bounding box and scaled to radius 1, so that an
// object's --scale is its radius in scene units.
#pragma once

#include "core/vec.h"

#include <cstdint>
#include <string>
#include <vector>

namespace lh {

struct TriangleMesh {
    std::vector<Vec3d> positions;
    std::vector<Vec3d> normals;     // per vertex, unit (smooth shading)
    std::vector<uint32_t> indices;  // 3 per triangle

    std::size_t triangleCount() const { return indices.size() / 3; }
    // Centres the mesh on its bounding box and scales it to a bounding radius of 1.
    void normalise();
    // p' = rotation * (scale * p) + translation; normals rotate with it.
    void transform(double scale, const Mat3d& rotation, const Vec3d& translation);
    // Computes area-weighted vertex normals (for meshes that have none).
    void computeNormals();
};

// Built-in shapes of radius 1: "sphere", "cube", "torus", "cylinder".
TriangleMesh builtinMesh(const std::string& name);
// Reads a Wavefront OBJ (triangulated on load). Throws FileError for missing or broken files
// and InputError for meshes without triangles.
TriangleMesh loadObj(const std::string& path);
// A built-in name or a path to an .obj file.
TriangleMesh loadMesh(const std::string& nameOrPath);

// Rotation from Euler angles in degrees, applied x, then y, then z.
Mat3d rotationFromDegrees(const Vec3d& degrees);

}  // namespace lh
