#pragma once
// Packs scene lights into the light texture (see bake/light_texture_layout.h).
#include <vector>

#include "base/uninitialised.h"
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
  UninitialisedVector<float> texels;  // kFloatsPerLight floats per light
  int pointStart = 0;                 // first point light; directional lights come before it
  int spotStart = 0;                  // first spot light; point lights come before it
};

// Packs `lights` in lightOrder(lights).
PackedLights packLights(const std::vector<Light>& lights);
// The texels of lights[order[0]], lights[order[1]], … (kFloatsPerLight floats each).
UninitialisedVector<float> packLightTexels(const std::vector<Light>& lights,
                                           const std::vector<int>& order);

// A spot's cone as the light texture holds it: the shader's falloff is
// smoothstep(clamp(cos · scale + offset, 0, 1)), cos to the spot's direction.
struct SpotConeTerms {
  float scale = 0.0f, offset = 1.0f;  // a light that is not a spot: always 1
};
SpotConeTerms spotConeTerms(const Light& light);

}  // namespace manylight
