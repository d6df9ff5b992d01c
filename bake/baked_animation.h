#pragma once
// The baked file's animation parts (docs/baked-format.md): node chains, shared by the cameras'
// section, and the light animation section. Internal to bake/.
#include "bake/baked_sections.h"
#include "scene/light_animation.h"

namespace manylight::baked {

inline constexpr std::uint32_t kLightAnimation = tag("LANI");

// A chain of animated nodes (root first) with their rest transforms and tracks.
void writeChain(Writer& w, const std::vector<AnimatedNode>& chain);
// Reads one; every track checked, and none with keys past `duration` seconds.
std::vector<AnimatedNode> readChain(Reader& r, float duration);

void writeLightAnimation(Writer& w, const LightAnimation& a);
// Reads the animation of a scene of `lights` lights: each animated light once, in increasing
// order, its chain and property tracks sound.
LightAnimation readLightAnimation(Reader& r, std::size_t lights);

}  // namespace manylight::baked
