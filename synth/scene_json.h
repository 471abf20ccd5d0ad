// scene.json: the full description of a synthetic scene (every primitive, texture, window
// view and the exposure), enough to rebuild it exactly, for the oracle volume and for anyone
// who wants to inspect or re-render an example.
#pragma once

#include "synth/radiance_field.h"
#include "synth/scene.h"

#include <string>

namespace lh::synth {

// The bake settings travel with the scene so that the oracle re-bakes the same light.
std::string sceneToJson(const Scene& scene, const BakeOptions& bake);
// Throws FileError naming `sourceName` if the text is not a valid scene description.
Scene sceneFromJson(const std::string& text, const std::string& sourceName,
                    BakeOptions* bake = nullptr);
Scene loadScene(const std::string& path, BakeOptions* bake = nullptr);

}  // namespace lh::synth
