#pragma once
// Packs scene lights into the light texture (see bake/light_texture_layout.h).
#include <vector>

#include "scene/scene.h"

namespace manylight {

// kFloatsPerLight floats per light, in the order of `lights`.
std::vector<float> packLights(const std::vector<Light>& lights);

}  // namespace manylight
