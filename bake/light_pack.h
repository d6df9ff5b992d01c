#pragma once
// Packs scene lights into the light texture (see bake/light_texture_layout.h).
#include <vector>

#include "scene/scene.h"

namespace manylight {

// The order of lights in the light texture: grouped by type (directional, point, spot), each
// group in scene order.
struct LightOrder {
  std::vector<int> scene;  // scene light index of each texture slot
  int pointStart = 0;      // first point light; directional lights come before it
  int spotStart = 0;       // first spot light; point lights come before it
};
LightOrder lightOrder(const std::vector<Light>& lights);

struct PackedLights {
  std::vector<float> texels;  // kFloatsPerLight floats per light
  int pointStart = 0;         // first point light; directional lights come before it
  int spotStart = 0;          // first spot light; point lights come before it
};

// Packs `lights` in lightOrder(lights).
PackedLights packLights(const std::vector<Light>& lights);

}  // namespace manylight
