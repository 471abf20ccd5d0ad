// Inserting virtual objects into a photograph, lit by a lighting volume.
//
// Every shading point is lit by rays traced from that point through the volume (emission-
// absorption exactly as the envmap renderer), not by one envmap per object: mirror = one
// reflected ray; glossy and diffuse = importance-sampled rays. Rays that meet another inserted
// object bounce off it (up to maxDepth). The real scene hides objects behind it: its depth
// along each pixel is where the volume's transmittance falls below 1/2. Shadows are
// differential, on the surfaces beneath an object (upward-facing, below its centre, within 3
// radii): the photo loses albedo x the incident light the objects block, with the incident
// light traced as cosine-weighted rays through the volume around the surface normal (from the
// density gradient) and the albedo estimated as photo / incident. Compositing is in linear
// radiance.
#pragma once

#include "core/camera.h"
#include "image/image.h"
#include "insert/material.h"
#include "insert/mesh.h"
#include "render/ray_marcher.h"

#include <string>
#include <vector>

namespace lh {

struct InsertedObject {
    TriangleMesh mesh;  // world coordinates
    Material material;
    Vec3d centre{0.0, 0.0, 0.0};
    double radius = 1;  // bounding radius, scene units
};

// Places a unit-radius mesh: scale = radius, then rotation, then translation to `at`.
InsertedObject placeObject(TriangleMesh mesh, const Material& material, const Vec3d& at,
                           double radius, const Mat3d& rotation = Mat3d::identity());

struct InsertOptions {
    int samples = 64;  // rays per pixel on glossy or diffuse objects (shared by its primary rays)
    int pixelSamples = 2;       // primary rays per pixel and axis (anti-aliased edges)
    int maxDepth = 3;           // object-to-object bounces
    bool singleEnvmap = false;  // light each object by one envmap at its centre instead
    int envmapHeight = 128;     // of those envmaps (width 2x)
    bool shadows = true;
    int shadowRays = 32;  // per background pixel near an object
    MarchOptions march;

    void validate() const;  // throws InputError
};

// How much of one object the camera sees, counted over the primary rays (pixelSamples^2 per
// pixel).
struct ObjectVisibility {
    long raysHit = 0;      // primary rays whose first inserted object is this one
    long raysVisible = 0;  // of those, rays that meet it before the real scene's surface
};

// `background` is the linear photograph seen by `camera` (same size). With `visibility`, also
// counts each object's rays (one entry per object, in order).
ImageRGB insertObjects(const RenderVolume& volume, const ImageRGB& background,
                       const PinholeCamera& camera, const std::vector<InsertedObject>& objects,
                       const InsertOptions& options = {},
                       std::vector<ObjectVisibility>* visibility = nullptr);

// Why `object` does not appear in the image, in words: behind the camera, outside the image,
// behind the real scene's surface, or behind another inserted object; "" when it is seen
// (visibility.raysVisible > 0).
std::string hiddenReason(const InsertedObject& object, const PinholeCamera& camera,
                         const ObjectVisibility& visibility);

}  // namespace lh
